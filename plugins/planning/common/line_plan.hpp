#pragma once
// The racing line for a track and a car, planned: the minimum-curvature line inside the edges less
// a margin (min_curvature.hpp), refined for minimum time under the car's limits (min_time.hpp).
// What `brickyard-plan line` writes with the same margin and limits, and what the planners use
// with `raceline plan`, so any track drives without a precomputed line. Framework-free.
#include "motion/speed_profile.hpp"
#include "track/centre_line.hpp"

namespace brickyard::planning {

// centre: the track's centre line with its widths. Throws std::invalid_argument for a track the
// optimiser cannot take (fewer than 4 points, widths missing).
track::CenterLine plan_line(const track::CenterLine& centre, const motion::VehicleLimits& limits, double margin);

}  // namespace brickyard::planning
