#include "pure_pursuit.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

CenterLine keep_inside(const CenterLine& line, const Track& track, double margin) {
  CenterLine out = line;
  int hint = -1;
  for (std::size_t i = 0; i < line.x.size(); ++i) {
    Frenet f = track.project(line.x[i], line.y[i], hint);
    hint = f.seg;
    const double lo = -track.width_right(f.seg, f.u) + margin, hi = track.width_left(f.seg, f.u) - margin;
    const double d = lo < hi ? std::clamp(f.d, lo, hi) : 0.5 * (lo + hi);
    if (d == f.d) continue;
    Frenet g = f;
    g.d = d;
    Eigen::Vector2d p = track.position(g);
    out.x[i] = p.x();
    out.y[i] = p.y();
  }
  return out;
}

RacingLine make_racing_line(const CenterLine& xy, const SpeedLimits& lim, double smooth_m) {
  RacingLine r;
  r.x = xy.x;
  r.y = xy.y;
  const int n = static_cast<int>(r.x.size());
  r.s.resize(n);
  std::vector<double> seg(n);
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    seg[i] = std::hypot(r.x[j] - r.x[i], r.y[j] - r.y[i]);
    if (i > 0) r.s[i] = r.s[i - 1] + seg[i - 1];
  }
  r.length = r.s[n - 1] + seg[n - 1];
  r.kappa = signed_curvature(xy, smooth_m);
  r.speed.resize(n);
  for (int i = 0; i < n; ++i)
    r.speed[i] = std::min(lim.v_max, std::sqrt(lim.a_lat / std::max(std::abs(r.kappa[i]), 1e-6)));
  // Two rounds around the closed loop so the passes settle across the start.
  for (int round = 0; round < 2; ++round) {
    for (int k = 2 * n; k > 0; --k) {  // backward: can we brake in time for the next point?
      int i = k % n, j = (k + 1) % n;
      r.speed[i] = std::min(r.speed[i], std::sqrt(r.speed[j] * r.speed[j] + 2 * lim.a_decel * seg[i]));
    }
    for (int k = 0; k < 2 * n; ++k) {  // forward: can we accelerate to it?
      int i = k % n, j = (k + 1) % n;
      r.speed[j] = std::min(r.speed[j], std::sqrt(r.speed[i] * r.speed[i] + 2 * lim.a_accel * seg[i]));
    }
  }
  return r;
}

int PurePursuit::nearest(double x, double y) {
  const int n = static_cast<int>(line_.x.size());
  auto d2 = [&](int i) { return (line_.x[i] - x) * (line_.x[i] - x) + (line_.y[i] - y) * (line_.y[i] - y); };
  int best = 0;
  if (hint_ < 0) {
    for (int i = 1; i < n; ++i)
      if (d2(i) < d2(best)) best = i;
  } else {
    best = hint_;
    for (int k = -20; k <= 20; ++k) {
      int i = ((hint_ + k) % n + n) % n;
      if (d2(i) < d2(best)) best = i;
    }
  }
  hint_ = best;
  return best;
}

Command PurePursuit::control(double x, double y, double yaw, double speed, double* target_speed) {
  const int n = static_cast<int>(line_.x.size());
  int i = nearest(x, y);
  const double ld = std::clamp(p_.lookahead_time * speed, p_.lookahead_min, p_.lookahead_max);
  // Walk along the line to the first point at least ld away.
  int j = i;
  for (int k = 0; k < n; ++k) {
    j = (i + k) % n;
    if (std::hypot(line_.x[j] - x, line_.y[j] - y) >= ld) break;
  }
  const double dx = line_.x[j] - x, dy = line_.y[j] - y;
  const double alpha = std::atan2(dy, dx) - yaw;
  const double dist = std::hypot(dx, dy);
  Command c;
  c.steer = std::clamp(std::atan2(2 * p_.wheelbase * std::sin(alpha), dist), -p_.max_steer, p_.max_steer);
  const double v_ref = line_.speed[i];
  const double u = p_.speed_gain * (v_ref - speed);
  c.throttle = std::clamp(u, 0.0, 1.0);
  c.brake = std::clamp(-u, 0.0, 1.0);
  if (target_speed) *target_speed = v_ref;
  return c;
}

}  // namespace brickyard::sim
