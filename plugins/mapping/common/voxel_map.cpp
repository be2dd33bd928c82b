#include "voxel_map.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

namespace {
std::int32_t cell(double v, float inv) { return static_cast<std::int32_t>(std::floor(v * inv)); }
}  // namespace

void VoxelMap::add(const Points& pts, const Covariances& covs) {
  // Two passes: each point's voxel numbered first (new voxels in first-met order), then the voxels
  // grown once to their new count and summed into. A map's millions of points grew them by
  // doubling, and each doubling's copy touched fresh pages: most of the start-up of a map.
  const std::size_t n = std::min(pts.size(), covs.size());
  std::vector<std::uint32_t> voxel_of(n, kSkipped);
  for (std::size_t i = 0; i < n; ++i) {
    if (!perception::in_range(pts[i]) || !covs[i].allFinite()) continue;
    const Eigen::Vector3d q = pts[i].cast<double>();
    bool inserted;
    voxel_of[i] = index_.find_or_insert(perception::cell_key(cell(q.x(), inv_), cell(q.y(), inv_), cell(q.z(), inv_)),
                                        static_cast<std::uint32_t>(index_.size()), inserted);
  }
  voxels_.resize(index_.size());
  targets_.resize(index_.size());
  is_touched_.resize(index_.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = voxel_of[i];
    if (v == kSkipped) continue;
    Voxel& x = voxels_[v];
    x.sum += pts[i].cast<double>();
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
