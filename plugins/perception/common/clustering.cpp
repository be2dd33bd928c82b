#include "clustering.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

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
  const float inv = 1.0f / p_.tolerance, tol2 = p_.tolerance * p_.tolerance;
  // Bucket the points by cell: count, then offsets, then fill (points of a cell contiguous).
  cells_.reset(static_cast<std::size_t>(n));
  key_.resize(n);
  for (int i = 0; i < n; ++i) {
    const Point& q = pts[i];
    key_[i] = cell_key(cell_of(q.x(), inv), cell_of(q.y(), inv), cell_of(q.z(), inv));
    bool inserted;
    ++cells_.find_or_insert(key_[i], Span{}, inserted).count;
  }
  // Spans placed in first-met order, so the layout does not depend on the table's slots.
  std::uint32_t offset = 0;
  order_.resize(n);
  for (int i = 0; i < n; ++i) {
    bool inserted;
    Span& s = cells_.find_or_insert(key_[i], Span{}, inserted);
    if (s.begin == kUnplaced) {
      s.begin = offset;
      offset += s.count;
    }
    order_[s.begin + s.filled++] = i;
  }
  // Union every pair closer than the tolerance.
  parent_.resize(n);
  for (int i = 0; i < n; ++i) parent_[i] = i;
  for (int i = 0; i < n; ++i) {
    const Point& q = pts[i];
    const std::int32_t cx = cell_of(q.x(), inv), cy = cell_of(q.y(), inv), cz = cell_of(q.z(), inv);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const Span* s = cells_.find(cell_key(cx + dx, cy + dy, cz + dz));
          if (!s) continue;
          for (std::uint32_t k = 0; k < s->count; ++k) {
            const int j = order_[s->begin + k];
            if (j <= i) continue;  // each pair once
            if (!((pts[j] - q).squaredNorm() < tol2)) continue;  // strict, as a radius search
            const int a = find(i), b = find(j);
            if (a != b) parent_[std::max(a, b)] = std::min(a, b);
          }
        }
  }
  // Components in order of their first point; sizes filtered.
  root_slot_.assign(n, -1);
  std::vector<std::vector<int>> all;
  for (int i = 0; i < n; ++i) {
    const int r = find(i);
    if (root_slot_[r] < 0) {
      root_slot_[r] = static_cast<int>(all.size());
      all.emplace_back();
    }
    all[root_slot_[r]].push_back(i);
  }
  for (auto& c : all)
    if (static_cast<int>(c.size()) >= p_.min_size && static_cast<int>(c.size()) <= p_.max_size) clusters.push_back(std::move(c));
}

}  // namespace brickyard::perception
