#pragma once
// The car's facts a path tracker drives with, from its description: wheelbase and steering limit
// (pure pursuit), the single-track model (lqr), the steering's delay, the powertrain and the grip
// (feedforward pedals). Framework-free.
#include "path_tracker.hpp"
#include "vehicle/vehicle.hpp"

#include <algorithm>

namespace brickyard::control {

inline void apply_vehicle(TrackerParams& p, const vehicle::Vehicle& car) {
  p.wheelbase = car.wheelbase;
  p.max_steer = car.max_steer;
  p.car = {car.mass, car.yaw_inertia, car.lf, car.lr, car.cornering_front, car.cornering_rear};
  p.steer_delay = car.steer_delay;
  p.powertrain = {car.mass, car.max_drive_force, car.max_power, car.max_brake_force,
                  0.5 * car.air_density * car.drag_area, car.rolling_resistance * car.mass * vehicle::gravity};
  p.grip = std::max(car.a_lat, car.a_decel);  // the planning envelope's: the friction circle with a margin
}

}  // namespace brickyard::control
