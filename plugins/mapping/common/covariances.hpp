#pragma once
// Each point's local shape as a covariance, from its k nearest neighbours: the per-point
// distributions of generalized ICP (Segal, Haehnel and Thrun, 2009) that the voxel map and the
// registration use. Framework-free.
#include "common/points.hpp"

#include <Eigen/Core>

#include <vector>

namespace brickyard::mapping {

using perception::Point;
using perception::Points;
using Covariance = Eigen::Matrix3f;
using Covariances = std::vector<Covariance, Eigen::aligned_allocator<Covariance>>;

struct CovarianceParams {
  int neighbours = 10;     // k nearest, the point itself among them
  float radius = 1.0f;     // m: neighbours are looked for no farther (a grid of this cell size)
  // GICP's plane regularization: the covariance's axes kept, its spreads made (1, 1, epsilon),
  // so every point is a small disc in its surface (a wall, the road) whatever the sampling.
  float epsilon = 1e-3f;
};

// One covariance per point. A point with fewer than 3 neighbours within the radius gets the
// identity (a sphere: it pulls toward the neighbour's mean in every direction, weakly).
Covariances point_covariances(const Points& pts, const CovarianceParams& p = {});

}  // namespace brickyard::mapping
