#include "covariances.hpp"

#include "common/cell_map.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>

namespace brickyard::mapping {

Covariances point_covariances(const Points& pts, const CovarianceParams& p) {
  const int n = static_cast<int>(pts.size());
  Covariances out(pts.size(), Covariance::Identity());
  if (n == 0) return out;
  // The points bucketed by grid cell (cells numbered first-met, each cell's points contiguous).
  const float inv = 1.0f / p.radius, r2 = p.radius * p.radius;
  perception::CellMap<std::uint32_t> cells;
  cells.reset(static_cast<std::size_t>(n));
  std::vector<std::uint32_t> cell(n);
  std::vector<std::array<std::int32_t, 3>> xyz;
  for (int i = 0; i < n; ++i) {
    const Point& q = pts[i];
    if (!perception::in_range(q)) { cell[i] = ~0u; continue; }
    const std::int32_t cx = perception::cell_of(q.x(), inv), cy = perception::cell_of(q.y(), inv), cz = perception::cell_of(q.z(), inv);
    bool inserted;
    cell[i] = cells.find_or_insert(perception::cell_key(cx, cy, cz), static_cast<std::uint32_t>(xyz.size()), inserted);
    if (inserted) xyz.push_back({cx, cy, cz});
  }
  std::vector<std::uint32_t> begin(xyz.size() + 1, 0), order(n);
  for (int i = 0; i < n; ++i)
    if (cell[i] != ~0u) ++begin[cell[i] + 1];
  for (std::size_t c = 0; c < xyz.size(); ++c) begin[c + 1] += begin[c];
  std::vector<std::uint32_t> fill(begin.begin(), begin.end() - 1);
  for (int i = 0; i < n; ++i)
    if (cell[i] != ~0u) order[fill[cell[i]]++] = static_cast<std::uint32_t>(i);
  // Per point: the k nearest among the 27 cells around it (a radius search: nothing farther than
  // the cell size is needed), then their covariance, regularized.
  std::vector<std::pair<float, std::uint32_t>> near;
  const int k = std::max(3, p.neighbours);
  for (int i = 0; i < n; ++i) {
    if (cell[i] == ~0u) continue;
    const Point& q = pts[i];
    const auto [cx, cy, cz] = xyz[cell[i]];
    near.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::uint32_t* c = cells.find(perception::cell_key(cx + dx, cy + dy, cz + dz));
          if (!c) continue;
          for (std::uint32_t a = begin[*c]; a < begin[*c + 1]; ++a) {
            const float d2 = (pts[order[a]] - q).squaredNorm();
            if (d2 <= r2) near.emplace_back(d2, order[a]);
          }
        }
    if (static_cast<int>(near.size()) < 3) continue;
    const int m = std::min<int>(k, static_cast<int>(near.size()));
    std::partial_sort(near.begin(), near.begin() + m, near.end());
    Eigen::Vector3f mean = Eigen::Vector3f::Zero();
    for (int j = 0; j < m; ++j) mean += pts[near[j].second];
    mean /= static_cast<float>(m);
    Covariance c = Covariance::Zero();
    for (int j = 0; j < m; ++j) {
      const Eigen::Vector3f d = pts[near[j].second] - mean;
      c += d * d.transpose();
    }
    c /= static_cast<float>(m);
    // Plane regularization: eigenvalues ascending, the smallest (the surface's normal) epsilon.
    Eigen::SelfAdjointEigenSolver<Covariance> es(c);
    const Eigen::Vector3f spread(p.epsilon, 1.0f, 1.0f);
    out[i] = es.eigenvectors() * spread.asDiagonal() * es.eigenvectors().transpose();
  }
  return out;
}

}  // namespace brickyard::mapping
