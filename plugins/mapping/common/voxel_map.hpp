#pragma once
// The target of voxelized GICP (Koide et al., 2021): a voxel grid whose voxels hold the mean of
// the points that fell in them and the mean of their covariances, so a source point is matched
// to one voxel by a hash lookup instead of a nearest-neighbour search. Points are added frame by
// frame (a map grows). Framework-free.
#include "covariances.hpp"
#include "common/cell_map.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::mapping {

struct Voxel {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();  // of the points
  Eigen::Matrix3d cov_sum = Eigen::Matrix3d::Zero();  // of their covariances
  std::uint32_t count = 0;
  Eigen::Vector3d mean() const { return sum / count; }
  Eigen::Matrix3d covariance() const { return cov_sum / count; }
};

class VoxelMap {
 public:
  explicit VoxelMap(float voxel = 1.0f) : voxel_(voxel), inv_(1.0f / voxel) { index_.reset(0); }
  float voxel_size() const { return voxel_; }
  // Adds points (map frame) with their covariances (map frame); points out of range are skipped.
  void add(const Points& pts, const Covariances& covs);
  // The voxel holding map point q, or null.
  const Voxel* at(const Eigen::Vector3d& q) const;
  std::size_t size() const { return voxels_.size(); }
  const std::vector<Voxel>& voxels() const { return voxels_; }

 private:
  float voxel_, inv_;
  perception::CellMap<std::uint32_t> index_;
  std::vector<Voxel> voxels_;  // first-added order
};

}  // namespace brickyard::mapping
