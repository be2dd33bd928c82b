#include "covariances.hpp"

#include "perception/common/cell_map.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>
#include <utility>
#include <vector>

namespace brickyard::mapping {

namespace {

// The unit eigenvector of c's smallest eigenvalue (the surface's normal): the eigenvalues by
// the cubic's closed form, then the kernel of c - lambda I as the longest cross product of two
// of its rows. Why not the whole decomposition: the regularized covariance needs this axis
// alone, and the other two cost as much again. Where the two smallest eigenvalues meet (the
// points on a line) the kernel is a plane: any direction across the line's row serves.
Eigen::Vector3f smallest_axis(const Covariance& c) {
  Eigen::SelfAdjointEigenSolver<Covariance> es;
  es.computeDirect(c, Eigen::EigenvaluesOnly);
  Covariance m = c;
  m.diagonal().array() -= es.eigenvalues()(0);
  const Eigen::Vector3f r0 = m.row(0), r1 = m.row(1), r2 = m.row(2);
  const Eigen::Vector3f x[3] = {r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  const float n[3] = {x[0].squaredNorm(), x[1].squaredNorm(), x[2].squaredNorm()};
  const int best = n[0] >= n[1] ? (n[0] >= n[2] ? 0 : 2) : (n[1] >= n[2] ? 1 : 2);
  const float scale = m.squaredNorm();
  if (n[best] > 1e-12f * scale * scale) return x[best] / std::sqrt(n[best]);
  const float l0 = r0.squaredNorm(), l1 = r1.squaredNorm(), l2 = r2.squaredNorm();
  const Eigen::Vector3f& row = l0 >= l1 ? (l0 >= l2 ? r0 : r2) : (l1 >= l2 ? r1 : r2);
  return row.squaredNorm() > 0 ? row.unitOrthogonal() : Eigen::Vector3f::UnitZ();
}

// The points bucketed by grid cell (cells numbered first-met, each cell's points contiguous).
struct CellBuckets {
  perception::CellMap<std::uint32_t> cells;      // cell key -> cell number
  std::vector<std::array<std::int32_t, 3>> xyz;  // per cell number: its grid coordinates
  std::vector<std::uint32_t> begin, order;       // cell c's points: order[begin[c]] up to order[begin[c + 1]]
};

CellBuckets bucket_by_cell(const Points& pts, float inv) {
  const int n = static_cast<int>(pts.size());
  CellBuckets b;
  b.cells.reset(static_cast<std::size_t>(n));
  std::vector<std::uint32_t> cell(n);
  for (int i = 0; i < n; ++i) {
    const Point& q = pts[i];
    if (!perception::in_range(q)) { cell[i] = ~0u; continue; }
    const std::int32_t cx = perception::cell_of(q.x(), inv), cy = perception::cell_of(q.y(), inv), cz = perception::cell_of(q.z(), inv);
    bool inserted;
    cell[i] = b.cells.find_or_insert(perception::cell_key(cx, cy, cz), static_cast<std::uint32_t>(b.xyz.size()), inserted);
    if (inserted) b.xyz.push_back({cx, cy, cz});
  }
  b.begin.assign(b.xyz.size() + 1, 0);
  b.order.assign(n, 0);
  for (int i = 0; i < n; ++i)
    if (cell[i] != ~0u) ++b.begin[cell[i] + 1];
  for (std::size_t c = 0; c < b.xyz.size(); ++c) b.begin[c + 1] += b.begin[c];
  std::vector<std::uint32_t> fill(b.begin.begin(), b.begin.end() - 1);
  for (int i = 0; i < n; ++i)
    if (cell[i] != ~0u) b.order[fill[cell[i]]++] = static_cast<std::uint32_t>(i);
  return b;
}

// The coordinates of the points of the 27 cells around one, gathered contiguous.
struct Gathered {
  std::vector<float> x, y, z;
};

void gather_around(const CellBuckets& b, const Points& pts, std::size_t cell_at, Gathered& g) {
  const auto [cx, cy, cz] = b.xyz[cell_at];
  g.x.clear(), g.y.clear(), g.z.clear();
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const std::uint32_t* c = b.cells.find(perception::cell_key(cx + dx, cy + dy, cz + dz));
        if (!c) continue;
        for (std::uint32_t a = b.begin[*c]; a < b.begin[*c + 1]; ++a) {
          const Point& q = pts[b.order[a]];
          g.x.push_back(q.x()), g.y.push_back(q.y()), g.z.push_back(q.z());
        }
      }
}

// The k nearest of the gathered points within the radius, for one point after another (its
// buffers and the last point's k-th distance kept from one to the next).
struct NearestSearch {
  int k;
  float r2;                                          // the radius, squared
  std::vector<float> gd;                             // per gathered point: its squared distance
  std::vector<std::uint32_t> cand;                   // the gathered points within the bound
  float last_kth = 0;                                // squared, of the point before; 0: none
  std::vector<std::pair<float, std::uint32_t>> best;  // the nearest, sorted: (squared distance, gathered index)

  NearestSearch(int k, float r2) : k(k), r2(r2), best(static_cast<std::size_t>(k)) {}

  // The distances first (a loop the compiler vectorizes), then the k smallest within the
  // radius, kept sorted (k is small). Returns how many were found (best's first ones).
  int find(const Gathered& g, const Point& q) {
    const std::size_t n = g.x.size();
    for (std::size_t j = 0; j < n; ++j) {
      const float dx = g.x[j] - q.x(), dy = g.y[j] - q.y(), dz = g.z[j] - q.z();
      gd[j] = dx * dx + dy * dy + dz * dz;
    }
    return keep_nearest(within_bound(n));
  }

  // Only the candidates within a bound are sorted: 1.5 times the last point's k-th distance
  // (points of a cell are alike spaced), else the radius. Gathered branch-free, in order:
  // with k of them the k nearest of all are among them (the same ones, ties included), and
  // the sort's mispredicted branches are for a few points, not for every one.
  std::size_t within_bound(std::size_t n) {
    float bound = last_kth > 0 ? std::min(r2, 2.25f * last_kth) : r2;
    std::size_t nc = 0;
    for (;;) {
      nc = 0;
      for (std::size_t j = 0; j < n; ++j) {
        cand[nc] = static_cast<std::uint32_t>(j);
        nc += gd[j] <= bound;
      }
      if (nc >= static_cast<std::size_t>(k) || bound >= r2) break;
      bound = r2;
    }
    return nc;
  }

  // The k nearest of the first nc candidates, by insertion into `best`.
  int keep_nearest(std::size_t nc) {
    int m = 0;
    float worst = r2;
    for (std::size_t a = 0; a < nc; ++a) {
      const std::uint32_t j = cand[a];
      const float d2 = gd[j];
      if (d2 > worst || (d2 == worst && m == k)) continue;
      int slot = m < k ? m++ : k - 1;
      while (slot > 0 && best[slot - 1].first > d2) {
        best[slot] = best[slot - 1];
        --slot;
      }
      best[slot] = {d2, j};
      if (m == k) worst = best[k - 1].first;
    }
    last_kth = m == k ? worst : 0;
    return m;
  }
};

// The covariance of the first m of `best`, read from the gathered copies (in cache), the upper
// triangle alone.
Covariance covariance_of_nearest(const Gathered& g, const std::vector<std::pair<float, std::uint32_t>>& best, int m) {
  float mx = 0, my = 0, mz = 0;
  for (int j = 0; j < m; ++j) mx += g.x[best[j].second], my += g.y[best[j].second], mz += g.z[best[j].second];
  const float inv_m = 1.0f / static_cast<float>(m);
  mx *= inv_m, my *= inv_m, mz *= inv_m;
  float c00 = 0, c01 = 0, c02 = 0, c11 = 0, c12 = 0, c22 = 0;
  for (int j = 0; j < m; ++j) {
    const std::uint32_t at_j = best[j].second;
    const float dx = g.x[at_j] - mx, dy = g.y[at_j] - my, dz = g.z[at_j] - mz;
    c00 += dx * dx, c01 += dx * dy, c02 += dx * dz, c11 += dy * dy, c12 += dy * dz, c22 += dz * dz;
  }
  Covariance c;
  c << c00, c01, c02, c01, c11, c12, c02, c12, c22;
  c *= inv_m;
  return c;
}

}  // namespace

Covariances point_covariances(const Points& pts, const CovarianceParams& p) {
  const Surfaces s = point_surfaces(pts, p);
  Covariances out(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) out[i] = covariance_of(s[i]);
  return out;
}

// The surfaces of the points of cells [first, last), written into `out` at the points' indices.
void surfaces_of_cells(const Points& pts, const CellBuckets& b, const CovarianceParams& p, std::size_t first, std::size_t last,
                       Surfaces& out) {
  const float flat = std::sqrt(std::max(0.0f, 1.0f - p.epsilon));
  // Cell by cell: the points of the 27 cells around it gathered once, contiguous, and for each of
  // the cell's points the k nearest of them within the radius (nothing farther than the cell size
  // is needed), then their covariance, regularized. (Gathered per point, the 27 lookups and the
  // scattered reads cost more than the distances.)
  NearestSearch search(std::max(3, p.neighbours), p.radius * p.radius);
  Gathered g;
  for (std::size_t cell_at = first; cell_at < last; ++cell_at) {
    gather_around(b, pts, cell_at, g);
    search.gd.resize(g.x.size());
    search.cand.resize(g.x.size());
    for (std::uint32_t at = b.begin[cell_at]; at < b.begin[cell_at + 1]; ++at) {
      const std::uint32_t i = b.order[at];
      const int m = search.find(g, pts[i]);
      if (m < 3) continue;
      // Plane regularization: spread 1 along the surface, epsilon along its normal.
      out[i] = flat * smallest_axis(covariance_of_nearest(g, search.best, m));
    }
  }
}

Surfaces point_surfaces(const Points& pts, const CovarianceParams& p, int threads) {
  Surfaces out(pts.size(), Eigen::Vector3f::Zero());
  if (pts.empty()) return out;
  const CellBuckets b = bucket_by_cell(pts, 1.0f / p.radius);
  const std::size_t cells = b.xyz.size();
  // Two threads take the cells' halves by points, not by cells: a frame's cells near the car hold
  // many more points than those far away. (A search's last k-th distance, carried from point to
  // point, only bounds which candidates it sorts, never which it finds: a half starting afresh
  // finds the same neighbours.)
  if (threads < 2 || pts.size() < 2048) {
    surfaces_of_cells(pts, b, p, 0, cells, out);
    return out;
  }
  const std::uint32_t half_points = b.begin[cells] / 2;
  const std::size_t middle = static_cast<std::size_t>(std::upper_bound(b.begin.begin(), b.begin.end() - 1, half_points) - b.begin.begin());
  std::thread second([&] { surfaces_of_cells(pts, b, p, middle, cells, out); });
  surfaces_of_cells(pts, b, p, 0, middle, out);
  second.join();
  return out;
}

}  // namespace brickyard::mapping
