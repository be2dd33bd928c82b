#include "vehicle_limits.hpp"

namespace brickyard::motion {

VehicleLimits vehicle_limits(const vehicle::Vehicle& p) {
  VehicleLimits l;
  l.v_max = p.v_max;
  l.a_lat = p.a_lat;
  l.a_accel = p.max_drive_force / p.mass;
  l.a_decel = p.a_decel;
  l.power = p.max_power / p.mass;
  l.drag = p.air_density * p.drag_area / (2 * p.mass);
  return l;
}

}  // namespace brickyard::motion
