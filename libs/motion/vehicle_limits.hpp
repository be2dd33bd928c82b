#pragma once
// A car's description as speed-profile limits: drive force, power and drag per mass from its
// powertrain and aero; top speed, lateral grip and braking from its planning envelope (the grip
// below μ g by a margin; downforce ignored). brickyard-plan's default car and the racing-line
// comparison's. Framework-free.
#include "speed_profile.hpp"

#include "vehicle/vehicle.hpp"

namespace brickyard::motion {

VehicleLimits vehicle_limits(const vehicle::Vehicle& car);

}  // namespace brickyard::motion
