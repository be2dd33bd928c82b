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
  const CenterLine line = track ? motion::keep_inside(xy, *track, p.edge_margin) : xy;
  DriverLine d;
  d.line = motion::make_racing_line(line, limits, p.curvature_smooth_m);
  d.planned_lap_s = planned_lap_s(d.line);
  return d;
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
