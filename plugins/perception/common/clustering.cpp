#include "clustering.hpp"

#include "packed_keys.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

namespace {

// The 13 neighbour offsets that come after (0, 0, 0) in lexicographic order.
constexpr int kForward[13][3] = {{0, 0, 1},  {0, 1, -1}, {0, 1, 0},  {0, 1, 1},  {1, -1, -1}, {1, -1, 0}, {1, -1, 1},
                                 {1, 0, -1}, {1, 0, 0},  {1, 0, 1},  {1, 1, -1}, {1, 1, 0},   {1, 1, 1}};

}  // namespace

int EuclideanClustering::find(int i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving
    i = parent_[i];
  }
  return i;
}

void EuclideanClustering::run(const Points& pts, std::vector<std::vector<int>>& clusters) {
  clusters.clear();
  const int n = static_cast<int>(pts.size());
  const float inv = 1.0f / p_.tolerance;
  // Cell keys in 32 bits when the points' cells fit (packed_keys.hpp), with a cell of margin all
  // round for the neighbours' keys.
  const Box box = box_of(pts);
  std::int32_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (box.in_range)
    for (int a = 0; a < 3; ++a) lo[a] = cell_of(box.lo[a], inv) - 1, hi[a] = cell_of(box.hi[a], inv) + 1;
  const Packing packing(lo, hi, 3);
  parent_.resize(n);
  for (int i = 0; i < n; ++i) parent_[i] = i;
  if (box.in_range && packing.ok)
    join_neighbours(pts, cells32_, [packing](std::int32_t x, std::int32_t y, std::int32_t z) { return packing.key(x, y, z); });
  else
    join_neighbours(pts, cells_, [](std::int32_t x, std::int32_t y, std::int32_t z) { return cell_key(x, y, z); });
  // Components in order of their first point; sizes filtered. Sizes first, so that only the
  // clusters kept are built, each allocated once.
  root_slot_.assign(n, -1);
  component_size_.clear();
  for (int i = 0; i < n; ++i) {
    int& slot = root_slot_[find(i)];
    if (slot < 0) {
      slot = static_cast<int>(component_size_.size());
      component_size_.push_back(0);
    }
    ++component_size_[slot];
  }
  for (int& size : component_size_) {  // now the cluster's number, or -1 when dropped
    const bool keep = size >= p_.min_size && size <= p_.max_size;
    if (keep) {
      clusters.emplace_back();
      clusters.back().reserve(size);
    }
    size = keep ? static_cast<int>(clusters.size()) - 1 : -1;
  }
  for (int i = 0; i < n; ++i) {
    const int c = component_size_[root_slot_[find(i)]];
    if (c >= 0) clusters[c].push_back(i);
  }
}

template <class Table, class Key> void EuclideanClustering::join_neighbours(const Points& pts, Table& cells, Key key) {
  const int n = static_cast<int>(pts.size());
  const float inv = 1.0f / p_.tolerance, tol2 = p_.tolerance * p_.tolerance;
  // Bucket the points by cell, cells numbered in first-met order (so nothing depends on the hash
  // table's slots): a cell's points are contiguous in order_.
  cells.reset(static_cast<std::size_t>(n));
  cell_of_point_.resize(n);
  cell_xyz_.clear();
  for (int i = 0; i < n; ++i) {
    const Point& q = pts[i];
    const std::int32_t cx = cell_of(q.x(), inv), cy = cell_of(q.y(), inv), cz = cell_of(q.z(), inv);
    bool inserted;
    const std::uint32_t c = cells.find_or_insert(key(cx, cy, cz), static_cast<std::uint32_t>(cell_xyz_.size()), inserted);
    if (inserted) cell_xyz_.push_back({cx, cy, cz});
    cell_of_point_[i] = c;
  }
  const std::size_t m = cell_xyz_.size();
  begin_.assign(m + 1, 0);
  for (int i = 0; i < n; ++i) ++begin_[cell_of_point_[i] + 1];
  for (std::size_t c = 0; c < m; ++c) begin_[c + 1] += begin_[c];
  order_.resize(n);
  fill_.assign(begin_.begin(), begin_.end() - 1);
  for (int i = 0; i < n; ++i) order_[fill_[cell_of_point_[i]]++] = i;
  // Union every pair closer than the tolerance (strictly, as a radius search): within a cell, and
  // between a cell and each of its 13 "forward" neighbours (the other 13 see it from their side).
  auto link = [&](int a, int b) {  // true when a and b are within the tolerance
    if (!((pts[a] - pts[b]).squaredNorm() < tol2)) return false;
    const int ra = find(a), rb = find(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
    return true;
  };
  for (std::size_t c = 0; c < m; ++c)
    for (std::uint32_t a = begin_[c]; a < begin_[c + 1]; ++a)
      for (std::uint32_t b = a + 1; b < begin_[c + 1]; ++b) link(order_[a], order_[b]);
  // A cell whose points are already one component ("whole") needs one link to a whole neighbour,
  // and none when the two are already joined: along a dense wall most are, by then.
  whole_.assign(m, 1);
  for (std::size_t c = 0; c < m; ++c) {
    const int r = find(order_[begin_[c]]);
    for (std::uint32_t a = begin_[c] + 1; a < begin_[c + 1] && whole_[c]; ++a) whole_[c] = find(order_[a]) == r;
  }
  for (std::size_t c = 0; c < m; ++c) {
    const std::uint32_t b0 = begin_[c], e0 = begin_[c + 1];
    const auto& [cx, cy, cz] = cell_xyz_[c];
    for (int k = 0; k < 13; ++k) {
      const std::uint32_t* nb = cells.find(key(cx + kForward[k][0], cy + kForward[k][1], cz + kForward[k][2]));
      if (!nb) continue;
      const std::uint32_t b1 = begin_[*nb], e1 = begin_[*nb + 1];
      const bool both_whole = whole_[c] && whole_[*nb];
      if (both_whole && find(order_[b0]) == find(order_[b1])) continue;
      bool linked = false;
      for (std::uint32_t a = b0; a < e0 && !(both_whole && linked); ++a)
        for (std::uint32_t b = b1; b < e1; ++b)
          if (link(order_[a], order_[b]) && both_whole) {
            linked = true;
            break;
          }
    }
  }
}

}  // namespace brickyard::perception
