#include "driver_line.hpp"

#include "motion/vehicle_limits.hpp"

#include <cmath>

namespace brickyard::sim {

motion::VehicleLimits profile_limits(const DriverProfile& p, const vehicle::Vehicle& car) {
  const motion::VehicleLimits& l = p.limits;
  motion::VehicleLimits limits = motion::independent_limits(l.v_max, l.a_lat, l.a_accel, l.a_decel);
  if (p.vehicle_limits) {
    limits = motion::vehicle_limits(car);
    limits.a_lat *= p.grip_use;
  }
  return limits;
}

DriverLine driver_line(const CenterLine& xy, const Track* track, const DriverProfile& p, const motion::VehicleLimits& limits) {
  const CenterLine moved = p.lateral_offset != 0 ? moved_across(xy, p.lateral_offset) : xy;
  const CenterLine line = track ? motion::keep_inside(moved, *track, p.edge_margin) : moved;
  DriverLine d;
  d.line = motion::make_racing_line(line, limits, p.curvature_smooth_m);
  if (p.speed_scale != 1)
    for (double& v : d.line.speed) v *= p.speed_scale;
  d.planned_lap_s = planned_lap_s(d.line);
  return d;
}

CenterLine moved_across(const CenterLine& xy, double offset) {
  CenterLine out = xy;
  const std::size_t n = xy.x.size();
  if (n < 3) return out;  // no normal to move along
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, b = (i + 1) % n;
    const double tx = xy.x[b] - xy.x[a], ty = xy.y[b] - xy.y[a], len = std::hypot(tx, ty);
    if (len <= 0) continue;
    out.x[i] = xy.x[i] - offset * ty / len;  // the left normal of (tx, ty) is (-ty, tx)
    out.y[i] = xy.y[i] + offset * tx / len;
  }
  return out;
}

double planned_lap_s(const motion::RacingLine& r) {
  std::vector<double> ds(r.x.size());
  for (std::size_t i = 0; i < r.x.size(); ++i) {
    const std::size_t j = (i + 1) % r.x.size();
    ds[i] = std::hypot(r.x[j] - r.x[i], r.y[j] - r.y[i]);
  }
  return motion::profile_time(ds, r.speed, true);
}

}  // namespace brickyard::sim
