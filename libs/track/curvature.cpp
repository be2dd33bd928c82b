#include "curvature.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace brickyard::track {

double menger_curvature(double ax, double ay, double bx, double by, double cx, double cy, double* sides) {
  // Lengths as sqrt(dx² + dy²) in this order (the simulator's track and banking were built with
  // it; hypot would move the last bits of every curvature and with them the runs' digests).
  const double e1x = bx - ax, e1y = by - ay, e2x = cx - bx, e2y = cy - by, e3x = cx - ax, e3y = cy - ay;
  const double l1 = std::sqrt(e1x * e1x + e1y * e1y), l2 = std::sqrt(e2x * e2x + e2y * e2y);
  const double l3 = std::sqrt(e3x * e3x + e3y * e3y);
  if (sides) *sides = l1 + l2;
  if (l1 * l2 * l3 <= 0) return 0;
  return 2 * (e1x * e2y - e1y * e2x) / (l1 * l2 * l3);
}

std::vector<double> signed_curvature(const CenterLine& c, double smooth_m) {
  const int n = static_cast<int>(c.x.size());
  std::vector<double> k(n);
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    k[i] = menger_curvature(c.x[a], c.y[a], c.x[i], c.y[i], c.x[b], c.y[b]);
  }
  if (smooth_m <= 0) return k;
  return cyclic_average(k, curvature_window(c, smooth_m));
}

int curvature_window(const CenterLine& c, double smooth_m) {
  if (smooth_m <= 0) return 0;
  const int n = static_cast<int>(c.x.size());
  double mean_len = 0;
  for (int i = 0; i < n; ++i) {
    const int b = (i + 1) % n;
    mean_len += Eigen::Vector2d(c.x[b] - c.x[i], c.y[b] - c.y[i]).norm() / n;
  }
  return std::max(0, static_cast<int>(std::round(smooth_m / mean_len / 2)));
}

std::vector<double> cyclic_average(const std::vector<double>& v, int half) {
  const int n = static_cast<int>(v.size());
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int j = -half; j <= half; ++j) sum += v[((i + j) % n + n) % n];
    out[i] = sum / (2 * half + 1);
  }
  return out;
}

}  // namespace brickyard::track
