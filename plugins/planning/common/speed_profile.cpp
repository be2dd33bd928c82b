#include "speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::planning {
namespace {
// Share of the longitudinal budget left at speed v on curvature k.
double budget(const VehicleLimits& l, double v, double k) {
  if (!l.ellipse) return 1.0;
  const double use = v * v * std::abs(k) / l.a_lat;
  return use >= 1 ? 0.0 : std::sqrt(1 - use * use);
}
}  // namespace

std::vector<double> speed_profile(const std::vector<double>& ds, const std::vector<double>& kappa,
                                  const VehicleLimits& l, bool closed, double v_start, double v_end,
                                  const std::vector<double>* cap) {
  const int n = static_cast<int>(kappa.size());
  if (n < 2 || static_cast<int>(ds.size()) != (closed ? n : n - 1))
    throw std::invalid_argument("speed profile: needs two points and one step per gap");
  std::vector<double> v(n);
  if (cap && static_cast<int>(cap->size()) != n) throw std::invalid_argument("speed profile: one cap per point");
  for (int i = 0; i < n; ++i) {
    v[i] = std::min(l.v_max, std::sqrt(l.a_lat / std::max(std::abs(kappa[i]), 1e-9)));
    if (cap) v[i] = std::min(v[i], std::max(0.0, (*cap)[i]));
  }
  if (!closed && v_end >= 0) v[n - 1] = std::min(v[n - 1], v_end);
  if (!closed && v_start >= 0) v[0] = std::min(v_start, l.v_max);
  // Accelerating from v over ds: the push (traction within the ellipse, at most power / v) less
  // drag; braking from the point after: the brakes within the ellipse plus drag.
  auto up = [&](double vi, double k, double step) {
    double push = l.a_accel * budget(l, vi, k);
    if (l.power > 0) push = std::min(push, l.power / std::max(vi, 1.0));
    const double a = push - l.drag * vi * vi;
    return std::sqrt(std::max(0.0, vi * vi + 2 * a * step));
  };
  auto down = [&](double vj, double k, double step) {
    const double a = l.a_decel * budget(l, vj, k) + l.drag * vj * vj;
    return std::sqrt(vj * vj + 2 * a * step);
  };
  const int rounds = closed ? 2 : 1;
  for (int round = 0; round < rounds; ++round) {
    if (closed) {
      for (int k = 2 * n; k > 0; --k) {
        const int i = k % n, j = (k + 1) % n;
        v[i] = std::min(v[i], down(v[j], kappa[j], ds[i]));
      }
      for (int k = 0; k < 2 * n; ++k) {
        const int i = k % n, j = (k + 1) % n;
        v[j] = std::min(v[j], up(v[i], kappa[i], ds[i]));
      }
    } else {
      for (int i = n - 2; i >= 0; --i) v[i] = std::min(v[i], down(v[i + 1], kappa[i + 1], ds[i]));
      // The car is at v_start whatever the line allows: it brakes as hard as it can from there.
      if (v_start >= 0) v[0] = std::min(v_start, l.v_max);
      for (int i = 0; i + 1 < n; ++i) v[i + 1] = std::min(v[i + 1], up(v[i], kappa[i], ds[i]));
    }
  }
  return v;
}

double profile_time(const std::vector<double>& ds, const std::vector<double>& v, bool closed) {
  const std::size_t n = v.size();
  double t = 0;
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const double a = v[i], b = v[closed ? (i + 1) % n : i + 1];
    t += ds[i] / std::max(0.5 * (a + b), 0.1);
  }
  return t;
}

}  // namespace brickyard::planning
