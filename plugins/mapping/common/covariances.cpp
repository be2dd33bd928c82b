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
  // Cell by cell: the points of the 27 cells around it gathered once, contiguous, and for each of
  // the cell's points the k nearest of them within the radius (nothing farther than the cell size
  // is needed), then their covariance, regularized. (Gathered per point, the 27 lookups and the
  // scattered reads cost more than the distances.)
  const int k = std::max(3, p.neighbours);
  std::vector<float> gx, gy, gz, gd;
  std::vector<std::uint32_t> gi;
  std::vector<std::pair<float, std::uint32_t>> best(static_cast<std::size_t>(k));
  for (std::size_t cell_at = 0; cell_at < xyz.size(); ++cell_at) {
    const auto [cx, cy, cz] = xyz[cell_at];
    gx.clear(), gy.clear(), gz.clear(), gi.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::uint32_t* c = cells.find(perception::cell_key(cx + dx, cy + dy, cz + dz));
          if (!c) continue;
          for (std::uint32_t a = begin[*c]; a < begin[*c + 1]; ++a) {
            const Point& q = pts[order[a]];
            gx.push_back(q.x()), gy.push_back(q.y()), gz.push_back(q.z()), gi.push_back(order[a]);
          }
        }
    const std::size_t g = gi.size();
    gd.resize(g);
    for (std::uint32_t at = begin[cell_at]; at < begin[cell_at + 1]; ++at) {
      const std::uint32_t i = order[at];
      const Point& q = pts[i];
      // The distances first (a loop the compiler vectorizes), then the k smallest within the
      // radius, kept sorted (k is small).
      for (std::size_t j = 0; j < g; ++j) {
        const float dx = gx[j] - q.x(), dy = gy[j] - q.y(), dz = gz[j] - q.z();
        gd[j] = dx * dx + dy * dy + dz * dz;
      }
      int m = 0;
      float worst = r2;
      for (std::size_t j = 0; j < g; ++j) {
        const float d2 = gd[j];
        if (d2 > worst || (d2 == worst && m == k)) continue;
        int slot = m < k ? m++ : k - 1;
        while (slot > 0 && best[slot - 1].first > d2) {
          best[slot] = best[slot - 1];
          --slot;
        }
        best[slot] = {d2, gi[j]};
        if (m == k) worst = best[k - 1].first;
      }
      if (m < 3) continue;
      Eigen::Vector3f mean = Eigen::Vector3f::Zero();
      for (int j = 0; j < m; ++j) mean += pts[best[j].second];
      mean /= static_cast<float>(m);
      Covariance c = Covariance::Zero();
      for (int j = 0; j < m; ++j) {
        const Eigen::Vector3f d = pts[best[j].second] - mean;
        c += d * d.transpose();
      }
      c /= static_cast<float>(m);
      // Plane regularization: eigenvalues ascending, the smallest (the surface's normal) epsilon.
      // The closed form (a cubic's roots): the iterative solver cost as much as the search.
      Eigen::SelfAdjointEigenSolver<Covariance> es;
      es.computeDirect(c);
      const Eigen::Vector3f spread(p.epsilon, 1.0f, 1.0f);
      out[i] = es.eigenvectors() * spread.asDiagonal() * es.eigenvectors().transpose();
    }
  }
  return out;
}

}  // namespace brickyard::mapping
