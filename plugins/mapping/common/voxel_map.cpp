#include "voxel_map.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

namespace {
std::int32_t cell(double v, float inv) { return static_cast<std::int32_t>(std::floor(v * inv)); }
}  // namespace

void VoxelMap::add(const Points& pts, const Covariances& covs) {
  for (std::size_t i = 0; i < pts.size() && i < covs.size(); ++i) {
    if (!perception::in_range(pts[i]) || !covs[i].allFinite()) continue;
    const Eigen::Vector3d q = pts[i].cast<double>();
    bool inserted;
    const std::uint32_t v = index_.find_or_insert(perception::cell_key(cell(q.x(), inv_), cell(q.y(), inv_), cell(q.z(), inv_)),
                                                  static_cast<std::uint32_t>(voxels_.size()), inserted);
    if (inserted) {
      voxels_.emplace_back();
      targets_.emplace_back();
      is_touched_.push_back(0);
    }
    Voxel& x = voxels_[v];
    x.sum += q;
    x.cov_sum += covs[i].cast<double>();
    ++x.count;
    if (!is_touched_[v]) is_touched_[v] = 1, touched_.push_back(v);
  }
  // The targets of the voxels this call touched, once each (an inverse per voxel, not per point).
  for (const std::uint32_t v : touched_) {
    const Voxel& x = voxels_[v];
    VoxelTarget& t = targets_[v];
    t.mean = x.mean().cast<float>();
    const Eigen::Matrix3d inv = (x.covariance() + Eigen::Matrix3d::Identity()).inverse();
    const float upper[6] = {float(inv(0, 0)), float(inv(0, 1)), float(inv(0, 2)), float(inv(1, 1)), float(inv(1, 2)), float(inv(2, 2))};
    std::copy(upper, upper + 6, t.inverse);
    t.count = static_cast<float>(x.count);
    is_touched_[v] = 0;
  }
  touched_.clear();
}

const Voxel* VoxelMap::at(const Eigen::Vector3d& q) const {
  if (!q.allFinite() || q.cwiseAbs().maxCoeff() > perception::kMaxCoordinate) return nullptr;
  const std::uint32_t* v = index_.find(perception::cell_key(cell(q.x(), inv_), cell(q.y(), inv_), cell(q.z(), inv_)));
  return v ? &voxels_[*v] : nullptr;
}

}  // namespace brickyard::mapping
