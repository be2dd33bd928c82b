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
  // The table maps a voxel's key to its number (first-met order); the sums are in a dense array.
  voxel_index_.reset(voxels_.size());  // last frame's count: the table grows if this one has more
  voxels_.clear();
  // Keys are computed kAhead points early, into a ring, and their slots prefetched: the loads
  // that a scattered hash makes of every point overlap instead of queueing.
  constexpr std::size_t kAhead = 8;
  constexpr std::uint64_t kSkip = ~std::uint64_t{0} - 1;  // no cell_key is this (63 bits at most)
  std::uint64_t ring[kAhead];
  const std::size_t n = in.size();
  auto key_of = [&](std::size_t j) {
    const Point& q = in[j];
    if (!in_range(q)) return kSkip;  // a NaN, or a huge value, must not reach an int cast
    return cell_key(cell_of(q.x(), inv_leaf), cell_of(q.y(), inv_leaf), cell_of(q.z(), inv_leaf));
  };
  for (std::size_t j = 0; j < kAhead && j < n; ++j) {
    ring[j] = key_of(j);
    voxel_index_.prefetch(ring[j]);
  }
  for (std::size_t j = 0; j < n; ++j) {
    const std::uint64_t key = ring[j % kAhead];
    if (j + kAhead < n) {
      ring[j % kAhead] = key_of(j + kAhead);
      voxel_index_.prefetch(ring[j % kAhead]);
    }
    if (key == kSkip) continue;
    const Point& q = in[j];
    bool inserted;
    const std::uint32_t i = voxel_index_.find_or_insert(key, static_cast<std::uint32_t>(voxels_.size()), inserted);
    if (inserted) voxels_.push_back(Voxel{0, 0, 0, 0});
    Voxel& v = voxels_[i];
    v.x += q.x();
    v.y += q.y();
    v.z += q.z();
    ++v.n;
  }
  const auto count = static_cast<std::uint32_t>(voxels_.size());
  out.voxels.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) out.voxels[i] = Point(voxels_[i].x, voxels_[i].y, voxels_[i].z) / static_cast<float>(voxels_[i].n);
  // 2. Votes per 2-D cell, over the hash table of occupied cells (which maps a cell to its
  // number; the cells themselves are in a dense array, first-met order).
  cells_.reset(cell_.size());
  cell_.clear();
  voxel_cell_.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const Point& v = out.voxels[i];
    const std::int32_t cx = cell_of(v.x(), inv_cell), cy = cell_of(v.y(), inv_cell);
    bool inserted;
    const std::uint32_t c = cells_.find_or_insert(cell_key(cx, cy, 0), static_cast<std::uint32_t>(cell_.size()), inserted);
    if (inserted) cell_.push_back(Cell{cx, cy, 0, v.z(), v.z(), 0});
    Cell& e = cell_[c];
    ++e.votes;
    e.zmin = std::min(e.zmin, v.z());
    e.zmax = std::max(e.zmax, v.z());
    voxel_cell_[i] = c;
  }
  // 3. Per cell, the height below which its voxels are ground (see the header). Only vertical
  // cells and their neighbours need a look around; they are few, so the walk starts from them.
  const std::uint32_t min_votes = static_cast<std::uint32_t>(p_.min_votes);
  auto vertical = [&](const Cell& c) { return c.votes >= min_votes && c.zmax - c.zmin >= p_.min_height; };
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (Cell& c : cell_) c.limit = vertical(c) ? -kInf : kInf;
  for (Cell& c : cell_) {
    if (!vertical(c)) continue;
    // Vertical: ground up to ground_band above the road it stands on, when a ground neighbour
    // confirms that height (the lowest one within ground_band; the band starts from the lower of
    // the two, so a cell whose lowest voxel is a wall's or a pylon's bottom measures from the
    // road beside it); none: vertical through. Its ground neighbours: ground, except what
    // stands min_height above this cell's foot (a wall leaning into them).
    float road = kInf;  // the lowest confirming neighbour
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const std::uint32_t* k = (dx || dy) ? cells_.find(cell_key(c.x + dx, c.y + dy, 0)) : nullptr;
        if (!k) continue;
        Cell& n = cell_[*k];
        if (vertical(n)) continue;
        n.limit = std::min(n.limit, c.zmin + p_.min_height);
        if (std::abs(n.zmin - c.zmin) <= p_.ground_band) road = std::min(road, n.zmin);
      }
    if (road < kInf) c.limit = std::min(c.zmin, road) + p_.ground_band;
  }
  out.ground.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) out.ground[i] = out.voxels[i].z() < cell_[voxel_cell_[i]].limit;
}

Points voxel_filter(const Points& in, float leaf) {
  GroundFilter f(GroundParams{leaf, 1.0f, 1, 0.0f, 0.0f});
  GroundResult r;
  f.run(in, r);
  return r.voxels;
}

}  // namespace brickyard::perception
