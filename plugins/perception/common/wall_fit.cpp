#include "wall_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::perception {

int longest_cluster_on_side(const Points& points, const std::vector<std::vector<int>>& clusters, int side) {
  int best = -1;
  float best_len = -1;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    float xmin = std::numeric_limits<float>::max(), xmax = std::numeric_limits<float>::lowest(), ysum = 0;
    for (int i : clusters[c]) {
      xmin = std::min(xmin, points[i].x());
      xmax = std::max(xmax, points[i].x());
      ysum += points[i].y();
    }
    if (ysum * static_cast<float>(side) <= 0) continue;
    if (xmax - xmin > best_len) {
      best_len = xmax - xmin;
      best = static_cast<int>(c);
    }
  }
  return best;
}

double poly_value(const std::vector<double>& c, double x, int derivative) {
  double y = 0;
  for (std::size_t k = c.size(); k-- > static_cast<std::size_t>(derivative);) {
    double f = c[k];
    for (int d = 0; d < derivative; ++d) f *= static_cast<double>(k - d);
    y = y * x + f;
  }
  return y;
}

WallFit fit_wall(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p) {
  WallFit w;
  w.cluster = longest_cluster_on_side(points, clusters, p.side);
  if (w.cluster < 0) return w;
  const std::vector<int>& idx = clusters[w.cluster];
  w.points = idx.size();
  const int n = static_cast<int>(idx.size()), terms = p.degree + 1 + (p.lean ? 1 : 0);
  if (n < std::max(p.min_points, terms)) return w;
  // x is scaled to [-1, 1] over the points' extent so the normal matrix stays well conditioned at
  // any degree; the coefficients are mapped back to metres below.
  w.x_min = std::numeric_limits<double>::max();
  w.x_max = std::numeric_limits<double>::lowest();
  for (int i : idx) {
    w.x_min = std::min(w.x_min, static_cast<double>(points[i].x()));
    w.x_max = std::max(w.x_max, static_cast<double>(points[i].x()));
  }
  const double mid = 0.5 * (w.x_min + w.x_max), half = std::max(0.5 * (w.x_max - w.x_min), 1e-3);
  Eigen::MatrixXd a(n, terms);
  Eigen::VectorXd b(n);
  for (int r = 0; r < n; ++r) {
    const Point& q = points[idx[r]];
    const double u = (q.x() - mid) / half;
    double pw = 1;
    for (int k = 0; k <= p.degree; ++k, pw *= u) a(r, k) = pw;
    if (p.lean) a(r, p.degree + 1) = q.z();
    b(r) = q.y();
  }
  const Eigen::VectorXd sol = a.colPivHouseholderQr().solve(b);
  w.residual = std::sqrt((a * sol - b).squaredNorm() / n);
  w.lean = p.lean ? sol(p.degree + 1) : 0.0;
  // p(u) with u = (x - mid) / half, expanded into powers of x: sum_k s_k ((x - mid)/half)^k.
  w.coefficients.assign(p.degree + 1, 0.0);
  std::vector<double> term(1, 1.0);  // coefficients of ((x - mid)/half)^k in powers of x
  for (int k = 0; k <= p.degree; ++k) {
    for (std::size_t j = 0; j < term.size(); ++j) w.coefficients[j] += sol(k) * term[j];
    std::vector<double> next(term.size() + 1, 0.0);
    for (std::size_t j = 0; j < term.size(); ++j) {
      next[j + 1] += term[j] / half;
      next[j] -= term[j] * mid / half;
    }
    term = std::move(next);
  }
  w.distance = poly_value(w.coefficients, 0.0);
  const double d1 = poly_value(w.coefficients, p.lookahead, 1), d2 = poly_value(w.coefficients, p.lookahead, 2);
  w.heading = std::atan(d1);
  w.curvature = d2 / std::pow(1 + d1 * d1, 1.5);
  w.valid = w.x_max - w.x_min >= p.min_length && w.residual <= p.max_residual && std::isfinite(w.distance);
  return w;
}

}  // namespace brickyard::perception
