#include "ground_filter.hpp"

#include "packed_keys.hpp"

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
  const std::size_t n = in.size();
  // 1. Voxels: accumulate each point into its voxel's sum. The table maps a voxel's key to its
  // number (first-met order); the sums are in a dense array. The keys are computed first, in a
  // loop of their own; when the frame's voxels fit 31 bits (any LiDAR frame: 400 m x 400 m x
  // 50 m is 2000 x 2000 x 250 voxels), keys and slots are 32-bit.
  const Box box = box_of(in);
  std::int32_t lo_cell[3], hi_cell[3];
  for (int a = 0; a < 3; ++a) {
    lo_cell[a] = box.in_range ? cell_of(box.lo[a], inv_leaf) : 0;
    hi_cell[a] = box.in_range ? cell_of(box.hi[a], inv_leaf) : 0;
  }
  const Packing voxel_packing(lo_cell, hi_cell, 3);
  const bool packed = box.in_range && voxel_packing.ok;
  // The sums go to an array already sized for the frame (new voxels are numbered in order): it
  // only ever grows, so a frame neither clears nor reallocates it.
  if (voxels_.size() < n) voxels_.resize(n);
  Voxel* sums = voxels_.data();
  auto accumulate = [&](auto& table, const auto& keys, auto skip) {
    table.reset(2 * voxel_count_);  // a quarter full at last frame's count: fewer probes
    table.number(keys.data(), n, skip, [&](std::size_t j, std::uint32_t i, bool inserted) {
      Voxel& v = sums[i];
      if (inserted) v = Voxel{0, 0, 0, 0};
      v.x += in[j].x();
      v.y += in[j].y();
      v.z += in[j].z();
      ++v.n;
    });
    voxel_count_ = table.size();
  };
  if (packed) {
    keys32_.resize(n);
    packed_keys(in, inv_leaf, voxel_packing, keys32_.data());
    accumulate(voxel_index32_, keys32_, ~std::uint32_t{0});  // no packed key is all ones (31 bits)
  } else {
    constexpr std::uint64_t kSkip = ~std::uint64_t{0} - 1;  // no cell_key is this (63 bits at most)
    keys64_.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const Point& q = in[j];  // a NaN, or a huge value, must not reach an int cast
      keys64_[j] = in_range(q) ? cell_key(cell_of(q.x(), inv_leaf), cell_of(q.y(), inv_leaf), cell_of(q.z(), inv_leaf)) : kSkip;
    }
    accumulate(voxel_index_, keys64_, kSkip);
  }
  const auto count = static_cast<std::uint32_t>(voxel_count_);
  out.voxels.resize(count);
  std::int32_t lo_2d[3] = {std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(), 0};
  std::int32_t hi_2d[3] = {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min(), 0};
  voxel_cell_.resize(count);
  cell_xy_.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const Point v = Point(voxels_[i].x, voxels_[i].y, voxels_[i].z) / static_cast<float>(voxels_[i].n);
    out.voxels[i] = v;
    const std::int32_t cx = cell_of(v.x(), inv_cell), cy = cell_of(v.y(), inv_cell);
    cell_xy_[i] = {cx, cy};
    lo_2d[0] = std::min(lo_2d[0], cx), hi_2d[0] = std::max(hi_2d[0], cx);
    lo_2d[1] = std::min(lo_2d[1], cy), hi_2d[1] = std::max(hi_2d[1], cy);
  }
  // 2. Votes per 2-D cell, over the hash table of occupied cells (which maps a cell to its
  // number; the cells themselves are in a dense array, first-met order). Packed as the voxels,
  // with a cell of margin all round so that step 3's neighbours have keys of their own.
  for (int a = 0; a < 2; ++a) lo_2d[a] -= 1, hi_2d[a] += 1;
  const Packing cell_packing(lo_2d, hi_2d, 3);
  if (count > 0 && cell_packing.ok)
    vote(cells32_, [cell_packing](std::int32_t x, std::int32_t y) { return cell_packing.key(x, y); }, out);
  else
    vote(cells_, [](std::int32_t x, std::int32_t y) { return cell_key(x, y, 0); }, out);
}

template <class Table, class Key> void GroundFilter::vote(Table& cells, Key key, GroundResult& out) {
  const auto count = static_cast<std::uint32_t>(out.voxels.size());
  // The cells' slots prefetched kAhead voxels early, as the voxels' (CellMap::number, which
  // measured slower here than this loop).
  constexpr std::uint32_t kAhead = 8;
  cells.reset(count);  // at most `count` cells: it never grows
  cell_.resize(count);
  std::uint32_t m = 0;  // cells so far
  for (std::uint32_t i = 0; i < kAhead && i < count; ++i) cells.prefetch(key(cell_xy_[i][0], cell_xy_[i][1]));
  for (std::uint32_t i = 0; i < count; ++i) {
    if (i + kAhead < count) cells.prefetch(key(cell_xy_[i + kAhead][0], cell_xy_[i + kAhead][1]));
    const float z = out.voxels[i].z();
    const auto [cx, cy] = cell_xy_[i];
    bool inserted;
    const std::uint32_t c = cells.find_or_insert(key(cx, cy), m, inserted);
    m += inserted;
    // Without a branch on `inserted` (a quarter to two fifths of the voxels start a cell, in no
    // pattern that a branch predictor would learn).
    Cell& e = cell_[c];
    e.x = cx;
    e.y = cy;
    e.votes = inserted ? 1 : e.votes + 1;
    e.zmin = inserted ? z : std::min(e.zmin, z);
    e.zmax = inserted ? z : std::max(e.zmax, z);
    voxel_cell_[i] = c;
  }
  cell_.resize(m);
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
        const std::uint32_t* k = (dx || dy) ? cells.find(key(c.x + dx, c.y + dy)) : nullptr;
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
