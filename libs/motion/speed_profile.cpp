#include "speed_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace brickyard::motion {
namespace {
// Share of the longitudinal budget left at speed v on curvature k.
double budget(const VehicleLimits& l, double v, double k) {
  if (!l.ellipse) return 1.0;
  const double use = v * v * std::abs(k) / l.a_lat;
  if (use >= 1) return 0.0;
  return l.ellipse_exponent == 2 ? std::sqrt(1 - use * use) : std::pow(1 - std::pow(use, l.ellipse_exponent), 1 / l.ellipse_exponent);
}

// A speed from a neighbour's and its slopes by that speed, the curvature and the step.
struct Link {
  double v = 0, dv = 0, dk = 0, dstep = 0;
};

// budget() and its slopes by v and k (the slope capped where the budget nears zero).
void budget_slope(const VehicleLimits& l, double v, double k, double& b, double& dv, double& dk) {
  b = budget(l, v, k), dv = dk = 0;
  if (!l.ellipse || b <= 0) return;
  // d b / d use = −use^(p−1) · b^(1−p): −use / b on the ellipse (p = 2).
  const double use = v * v * std::abs(k) / l.a_lat, p = l.ellipse_exponent;
  const double slope = p == 2 ? -use / std::max(b, 0.05) : -std::pow(use, p - 1) * std::pow(std::max(b, 0.05), 1 - p);
  dv = slope * 2 * v * std::abs(k) / l.a_lat;
  dk = slope * v * v * (k < 0 ? -1 : 1) / l.a_lat;
}

// speed_profile's push from the previous point (vi, k, step) and brake to the next (vj, k, step).
Link push_link(const VehicleLimits& l, double vi, double k, double step) {
  double b, bv, bk;
  budget_slope(l, vi, k, b, bv, bk);
  double push = l.a_accel * b, pv = l.a_accel * bv, pk = l.a_accel * bk;
  if (l.power > 0 && l.power / std::max(vi, 1.0) < push) {
    push = l.power / std::max(vi, 1.0);
    pv = vi > 1 ? -l.power / (vi * vi) : 0.0;
    pk = 0;
  }
  const double a = push - l.drag * vi * vi, w = vi * vi + 2 * a * step;
  if (w <= 0) return {};
  const double r = std::sqrt(w);
  return {r, (vi + step * (pv - 2 * l.drag * vi)) / r, step * pk / r, a / r};
}

Link brake_link(const VehicleLimits& l, double vj, double k, double step) {
  double b, bv, bk;
  budget_slope(l, vj, k, b, bv, bk);
  const double a = l.a_decel * b + l.drag * vj * vj, r = std::sqrt(vj * vj + 2 * a * step);
  if (r <= 0) return {};
  return {r, (vj + step * (l.a_decel * bv + 2 * l.drag * vj)) / r, step * l.a_decel * bk / r, a / r};
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

double closed_lap_time_gradient(const std::vector<double>& ds, const std::vector<double>& kappa, const VehicleLimits& l,
                                std::vector<double>& d_kappa, std::vector<double>& d_ds) {
  const int n = static_cast<int>(kappa.size());
  const std::vector<double> v = speed_profile(ds, kappa, l, true);
  std::vector<double> adj(n, 0.0);  // dT/dv_i, direct at first, then with what flows in
  d_kappa.assign(n, 0.0);
  d_ds.assign(n, 0.0);
  double t = 0;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double m = 0.5 * (v[i] + v[j]);
    if (m <= 0.1) {
      t += ds[i] / 0.1, d_ds[i] += 1 / 0.1;
      continue;
    }
    t += ds[i] / m;
    d_ds[i] += 1 / m;
    adj[i] -= 0.5 * ds[i] / (m * m);
    adj[j] -= 0.5 * ds[i] / (m * m);
  }
  // Each speed's source: -1 its own cap, else the neighbour whose link sets it (ties: the cap).
  std::vector<int> from(n, -1), children(n, 0);
  std::vector<Link> link(n);
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n, next = (i + 1) % n;
    const double cap = std::min(l.v_max, std::sqrt(l.a_lat / std::max(std::abs(kappa[i]), 1e-9)));
    const Link brake = brake_link(l, v[next], kappa[next], ds[i]), push = push_link(l, v[prev], kappa[prev], ds[prev]);
    double best = cap;
    if (brake.v < best) best = brake.v, from[i] = next, link[i] = brake;
    if (push.v < best) from[i] = prev, link[i] = push;
    if (from[i] >= 0) ++children[from[i]];
  }
  // Reverse accumulation in dependency order (a speed's sensitivity is complete once every speed
  // set from it has passed its own on); links that close a loop, if any, carry nothing.
  std::vector<int> ready;
  for (int i = 0; i < n; ++i)
    if (children[i] == 0) ready.push_back(i);
  while (!ready.empty()) {
    const int i = ready.back();
    ready.pop_back();
    const int f = from[i];
    if (f < 0) {
      const double cap = std::sqrt(l.a_lat / std::max(std::abs(kappa[i]), 1e-9));
      if (cap < l.v_max && std::abs(kappa[i]) > 1e-9) d_kappa[i] += adj[i] * -0.5 * cap / kappa[i];
      continue;
    }
    adj[f] += adj[i] * link[i].dv;
    d_kappa[f] += adj[i] * link[i].dk;
    d_ds[f == (i + 1) % n ? i : f] += adj[i] * link[i].dstep;  // the step between i and f
    if (--children[f] == 0) ready.push_back(f);
  }
  return t;
}

}  // namespace brickyard::motion
