#include "ground_filter.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

Points GroundResult::obstacles() const {
  Points out;
  for (std::size_t i = 0; i < voxels.size(); ++i)
    if (!ground[i]) out.push_back(voxels[i]);
  return out;
}

void GroundFilter::run(const Points& in, GroundResult& out) {
  const float inv_leaf = 1.0f / p_.leaf, inv_cell = 1.0f / p_.cell;
  // 1. Voxels: accumulate each point into its voxel's sum.
  voxel_index_.reset(in.size());
  voxels_.clear();
  for (const Point& q : in) {
    if (!q.allFinite()) continue;
    bool inserted;
    std::uint32_t& v = voxel_index_.find_or_insert(
        cell_key(cell_of(q.x(), inv_leaf), cell_of(q.y(), inv_leaf), cell_of(q.z(), inv_leaf)),
        static_cast<std::uint32_t>(voxels_.size()), inserted);
    if (inserted) voxels_.push_back({Eigen::Vector3f::Zero(), 0, v});
    voxels_[v].sum += q;
    ++voxels_[v].n;
  }
  out.voxels.resize(voxels_.size());
  for (std::size_t i = 0; i < voxels_.size(); ++i) out.voxels[i] = voxels_[i].sum / static_cast<float>(voxels_[i].n);
  // 2. Votes per 2-D cell, over the hash table of occupied cells.
  cells_.reset(out.voxels.size());
  for (const Point& v : out.voxels) {
    bool inserted;
    Cell& c = cells_.find_or_insert(cell_key(cell_of(v.x(), inv_cell), cell_of(v.y(), inv_cell), 0), Cell{0, v.z(), v.z()}, inserted);
    ++c.votes;
    c.zmin = std::min(c.zmin, v.z());
    c.zmax = std::max(c.zmax, v.z());
  }
  out.ground.resize(out.voxels.size());
  for (std::size_t i = 0; i < out.voxels.size(); ++i) {
    const Point& v = out.voxels[i];
    const Cell* c = cells_.find(cell_key(cell_of(v.x(), inv_cell), cell_of(v.y(), inv_cell), 0));
    const bool vertical = c->votes >= static_cast<std::uint32_t>(p_.min_votes) && c->zmax - c->zmin >= p_.min_height;
    out.ground[i] = !vertical || v.z() - c->zmin < p_.ground_band;
  }
}

Points voxel_filter(const Points& in, float leaf) {
  GroundFilter f(GroundParams{leaf, 1.0f, 1, 0.0f, 0.0f});
  GroundResult r;
  f.run(in, r);
  return r.voxels;
}

}  // namespace brickyard::perception
