#pragma once
// The target of voxelized GICP (Koide et al., 2021): a voxel grid whose voxels hold the mean of
// the points that fell in them and the mean of their covariances, so a source point is matched
// to one voxel by a hash lookup instead of a nearest-neighbour search. Points are added frame by
// frame (a map grows). Framework-free.
#include "covariances.hpp"
#include "perception/common/cell_map.hpp"

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

// What a registration reads of a voxel, kept up to date as points are added, in float (the
// registration's arithmetic): its mean, its count and (Sigma_v + I)^-1 of its mean covariance
// Sigma_v. Why that inverse: a scan point's covariance is I - s s^T (covariances.hpp), so the
// inverse the registration takes of Sigma_v + I - s s^T is this one plus a rank-one term
// (Sherman-Morrison), with no 3x3 inverse per point.
struct VoxelTarget {
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  float inverse[6] = {1, 0, 0, 1, 0, 1};  // its upper triangle: 00 01 02 11 12 22
  float count = 0;
};

class VoxelMap {
 public:
  explicit VoxelMap(float voxel = 1.0f) : voxel_(voxel), inv_(1.0f / voxel) { index_.reset(0); }
  float voxel_size() const { return voxel_; }
  // Adds points (map frame) with their covariances (map frame); points out of range are skipped.
  void add(const Points& pts, const Covariances& covs);
  // The voxel holding map point q, or null.
  const Voxel* at(const Eigen::Vector3d& q) const;
  // Its target, or null.
  const VoxelTarget* target(const Eigen::Vector3f& q) const { return target(key(q)); }
  // The same in two steps, so a loop can prefetch a point's voxel a few points ahead of reading
  // it (the lookups of a scan's points are scattered over the map: each a cache miss).
  static constexpr std::uint64_t kNoKey = ~std::uint64_t{0};
  std::uint64_t key(const Eigen::Vector3f& q) const {
    if (!perception::in_range(q)) return kNoKey;
    return perception::cell_key(perception::cell_of(q.x(), inv_), perception::cell_of(q.y(), inv_), perception::cell_of(q.z(), inv_));
  }
  void prefetch(std::uint64_t key) const {
    if (key != kNoKey) index_.prefetch(key);
  }
  const VoxelTarget* target(std::uint64_t key) const {
    if (key == kNoKey) return nullptr;
    const std::uint32_t* v = index_.find(key);
    return v ? &targets_[*v] : nullptr;
  }
  std::size_t size() const { return voxels_.size(); }
  const std::vector<Voxel>& voxels() const { return voxels_; }

 private:
  static constexpr std::uint32_t kSkipped = ~std::uint32_t{0};  // a point out of range
  float voxel_, inv_;
  perception::CellMap<std::uint32_t> index_;
  std::vector<Voxel> voxels_;  // first-added order
  std::vector<VoxelTarget, perception::HugePageAllocator<VoxelTarget>> targets_;  // the same order
  std::vector<std::uint32_t> touched_;  // by the add() under way, each once
  std::vector<char> is_touched_;        // per voxel
};

}  // namespace brickyard::mapping
