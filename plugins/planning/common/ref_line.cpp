#include "ref_line.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::planning {

RefLine::RefLine(std::vector<double> x, std::vector<double> y, std::vector<double> kappa)
    : x_(std::move(x)), y_(std::move(y)), kappa_(std::move(kappa)) {
  const int n = size();
  if (n < 3 || static_cast<int>(y_.size()) != n || static_cast<int>(kappa_.size()) != n)
    throw std::invalid_argument("reference line: needs at least 3 points, with x, y and curvature each");
  s_.resize(n + 1, 0.0);
  std::vector<Eigen::Vector2d> seg_n(n);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double dx = x_[j] - x_[i], dy = y_[j] - y_[i], len = std::hypot(dx, dy);
    if (!(len > 1e-6)) throw std::invalid_argument("reference line: points " + std::to_string(i) + " and " + std::to_string(j) + " coincide");
    s_[i + 1] = s_[i] + len;
    seg_n[i] = Eigen::Vector2d(-dy, dx) / len;
  }
  length_ = s_[n];
  n_.resize(n);
  for (int i = 0; i < n; ++i) n_[i] = (seg_n[i] + seg_n[(i + n - 1) % n]).normalized();
}

double RefLine::wrap(double s) const {
  s = std::fmod(s, length_);
  return s < 0 ? s + length_ : s;
}

int RefLine::segment(double s, double* u) const {
  s = wrap(s);
  int i = static_cast<int>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin()) - 1;
  i = std::clamp(i, 0, size() - 1);
  *u = (s - s_[i]) / (s_[i + 1] - s_[i]);
  return i;
}

Eigen::Vector2d RefLine::normal(double s) const {
  double u;
  const int i = segment(s, &u), j = (i + 1) % size();
  return ((1 - u) * n_[i] + u * n_[j]).normalized();
}

Eigen::Vector2d RefLine::point(double s, double d) const {
  double u;
  const int i = segment(s, &u), j = (i + 1) % size();
  const Eigen::Vector2d p((1 - u) * x_[i] + u * x_[j], (1 - u) * y_[i] + u * y_[j]);
  return p + d * ((1 - u) * n_[i] + u * n_[j]).normalized();
}

double RefLine::heading(double s) const {
  const Eigen::Vector2d n = normal(s);
  return std::atan2(-n.x(), n.y());
}

double RefLine::kappa(double s) const { return interpolate(kappa_, s); }

double RefLine::interpolate(const std::vector<double>& v, double s) const {
  double u;
  const int i = segment(s, &u);
  return (1 - u) * v[i] + u * v[(i + 1) % size()];
}

Eigen::Vector2d RefLine::project_on(int i, double x, double y) const {
  const int j = (i + 1) % size();
  const double dx = x_[j] - x_[i], dy = y_[j] - y_[i], len = s_[i + 1] - s_[i];
  const double u = std::clamp(((x - x_[i]) * dx + (y - y_[i]) * dy) / (len * len), 0.0, 1.0);
  const double s = s_[i] + u * len;
  const Eigen::Vector2d n = ((1 - u) * n_[i] + u * n_[j]).normalized();
  const Eigen::Vector2d p(x_[i] + u * dx, y_[i] + u * dy);
  return {s, (Eigen::Vector2d(x, y) - p).dot(n)};
}

Eigen::Vector2d RefLine::to_frenet(double x, double y, double hint_s) const {
  const int n = size();
  auto dist2 = [&](int i) {  // to the nearest point of the straight segment
    const int j = (i + 1) % n;
    const double dx = x_[j] - x_[i], dy = y_[j] - y_[i], len = s_[i + 1] - s_[i];
    const double u = std::clamp(((x - x_[i]) * dx + (y - y_[i]) * dy) / (len * len), 0.0, 1.0);
    const double ex = x - x_[i] - u * dx, ey = y - y_[i] - u * dy;
    return ex * ex + ey * ey;
  };
  int best = -1;
  double best_d2 = 0;
  if (hint_s >= 0) {
    double u;
    const int h = segment(hint_s, &u);
    constexpr int kWindow = 20;
    int at = 0;
    for (int k = -kWindow; k <= kWindow; ++k) {
      const int i = ((h + k) % n + n) % n;
      const double d2 = dist2(i);
      if (best < 0 || d2 < best_d2) { best = i; best_d2 = d2; at = k; }
    }
    if (std::abs(at) == kWindow) best = -1;  // still going down at the window's edge: search all
  }
  if (best < 0) {
    for (int i = 0; i < n; ++i) {
      const double d2 = dist2(i);
      if (best < 0 || d2 < best_d2) { best = i; best_d2 = d2; }
    }
  }
  return project_on(best, x, y);
}

}  // namespace brickyard::planning
