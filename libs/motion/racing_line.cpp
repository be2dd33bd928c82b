#include "racing_line.hpp"

#include <cstdio>

#include "track/curvature.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::motion {

track::CenterLine keep_inside(const track::CenterLine& line, const track::Track& track, double margin) {
  track::CenterLine out = line;
  int hint = -1;
  for (std::size_t i = 0; i < line.x.size(); ++i) {
    track::Frenet f = track.project(line.x[i], line.y[i], hint);
    hint = f.seg;
    const double lo = -track.width_right(f.seg, f.u) + margin, hi = track.width_left(f.seg, f.u) - margin;
    const double d = lo < hi ? std::clamp(f.d, lo, hi) : 0.5 * (lo + hi);
    if (d == f.d) continue;
    track::Frenet g = f;
    g.d = d;
    Eigen::Vector2d p = track.position(g);
    out.x[i] = p.x();
    out.y[i] = p.y();
  }
  return out;
}

std::string leaves_track(const track::CenterLine& line, const track::Track& track) {
  int hint = -1;
  for (std::size_t i = 0; i < line.x.size(); ++i) {
    const track::Frenet f = track.project(line.x[i], line.y[i], hint);
    hint = f.seg;
    const double left = track.width_left(f.seg, f.u), right = track.width_right(f.seg, f.u);
    const double out = f.d > left ? f.d - left : -f.d > right ? -f.d - right : 0.0;
    if (out > 0) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "point %zu (%.2f, %.2f) is %.2f m beyond the track's %s edge at s = %.1f m", i + 1,
                    line.x[i], line.y[i], out, f.d > 0 ? "left" : "right", f.s);
      return buf;
    }
  }
  return {};
}

RacingLine make_racing_line(const track::CenterLine& xy, const VehicleLimits& lim, double smooth_m) {
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
  r.kappa = track::signed_curvature(xy, smooth_m);
  r.speed = speed_profile(seg, r.kappa, lim, true);
  return r;
}

VehicleLimits independent_limits(double v_max, double a_lat, double a_accel, double a_decel) {
  VehicleLimits l;
  l.v_max = v_max;
  l.a_lat = a_lat;
  l.a_accel = a_accel;
  l.a_decel = a_decel;
  l.drag = 0;
  l.power = 0;
  l.ellipse = false;
  return l;
}

}  // namespace brickyard::motion
