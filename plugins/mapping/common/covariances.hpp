#pragma once
// Each point's local shape as a covariance, from its k nearest neighbours: the per-point
// distributions of generalized ICP (Segal, Haehnel and Thrun, 2009) that the voxel map and the
// registration use. Framework-free.
#include "perception/common/points.hpp"

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

// Each point's regularized covariance, I - (1 - epsilon) n n^T for its surface normal n, held as
// the one vector s = sqrt(1 - epsilon) n, its covariance I - s s^T: what the registration needs
// of it (three floats, not nine, and the inverse it takes has a closed form, vgicp.cpp). A point
// with fewer than 3 neighbours within the radius gets s = 0, the identity (a sphere: it pulls
// toward the neighbour's mean in every direction, weakly).
// `threads` (1 or 2) share the points' cells: each point's surface is its own, so the result is
// the same bit for bit on either.
using Surfaces = std::vector<Eigen::Vector3f>;
Surfaces point_surfaces(const Points& pts, const CovarianceParams& p = {}, int threads = 1);

inline Covariance covariance_of(const Eigen::Vector3f& s) { return Covariance::Identity() - s * s.transpose(); }

// The same as covariance matrices.
Covariances point_covariances(const Points& pts, const CovarianceParams& p = {});

}  // namespace brickyard::mapping
