#include "ground_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
    Cell& c = cells_.find_or_insert(cell_key(cell_of(v.x(), inv_cell), cell_of(v.y(), inv_cell), 0), Cell{0, v.z(), v.z(), 0.0f, false}, inserted);
    ++c.votes;
    c.zmin = std::min(c.zmin, v.z());
    c.zmax = std::max(c.zmax, v.z());
  }
  // 3. Per cell, once: the height below which its voxels are ground (see the header).
  const std::uint32_t min_votes = static_cast<std::uint32_t>(p_.min_votes);
  auto vertical = [&](const Cell& c) { return c.votes >= min_votes && c.zmax - c.zmin >= p_.min_height; };
  constexpr float kInf = std::numeric_limits<float>::infinity();
  out.ground.resize(out.voxels.size());
  for (std::size_t i = 0; i < out.voxels.size(); ++i) {
    const Point& v = out.voxels[i];
    const std::int32_t cx = cell_of(v.x(), inv_cell), cy = cell_of(v.y(), inv_cell);
    Cell* c = cells_.find_mutable(cell_key(cx, cy, 0));
    if (!c->resolved) {
      c->resolved = true;
      const bool vert = vertical(*c);
      // Vertical: ground up to ground_band above the road it stands on, when a ground neighbour
      // confirms that height (the one nearest in height; the band starts from the lower of the
      // two, so a cell whose lowest voxel is a wall's bottom measures from the road beside it);
      // none: vertical through. Not vertical: ground, except what stands min_height above a
      // vertical neighbour's foot (a wall leaning into this cell).
      float best = p_.ground_band;
      c->limit = vert ? -kInf : kInf;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          const Cell* n = (dx || dy) ? cells_.find(cell_key(cx + dx, cy + dy, 0)) : nullptr;
          if (!n) continue;
          if (!vert) {
            if (vertical(*n)) c->limit = std::min(c->limit, n->zmin + p_.min_height);
          } else if (!vertical(*n) && std::abs(n->zmin - c->zmin) <= best) {
            best = std::abs(n->zmin - c->zmin);
            c->limit = std::min(c->zmin, n->zmin) + p_.ground_band;
          }
        }
    }
    out.ground[i] = v.z() < c->limit;
  }
}

Points voxel_filter(const Points& in, float leaf) {
  GroundFilter f(GroundParams{leaf, 1.0f, 1, 0.0f, 0.0f});
  GroundResult r;
  f.run(in, r);
  return r.voxels;
}

}  // namespace brickyard::perception
