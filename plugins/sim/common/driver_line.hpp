#pragma once
// The ground-truth driver's line: the limits its speed profile plans with (the graph's, or the
// car's envelope with a grip margin), the racing line kept inside the track, its speed profile,
// and the lap time that profile plans (what a driven lap is measured against, docs/control.md).
// Framework-free: the truth_follower node hands the line to the path tracker.
#include "track.hpp"

#include "control/path_tracker.hpp"
#include "motion/racing_line.hpp"
#include "vehicle/vehicle.hpp"

namespace brickyard::sim {

// The driver's own tracker defaults: a look-ahead a little longer than the car stack's tracker.
inline control::TrackerParams driver_tracker_defaults() {
  control::TrackerParams t;
  t.lookahead_min = 12;
  return t;
}

struct DriverProfile {
  motion::VehicleLimits limits;  // v_max and the accelerations bound; independent_limits() sets the rest
  bool vehicle_limits = false;   // true: the vehicle file's envelope instead (ellipse, drag, power)
  double grip_use = 0.93;        // with it: the share of its lateral grip the profile plans with
  double curvature_smooth_m = 30;
  double edge_margin = 2.5;  // m: closest the line's points may come to a track edge
  // A rival's driver (issue 46): its line moved across by this (m, left positive; then kept inside
  // the track), and the profile's speeds times speed_scale (a car at 80 % of the line's pace).
  double lateral_offset = 0;
  double speed_scale = 1;
};

// The limits the speed profile plans with.
motion::VehicleLimits profile_limits(const DriverProfile& p, const vehicle::Vehicle& car);

struct DriverLine {
  motion::RacingLine line;
  double planned_lap_s = 0;
};
// The racing line through `xy` (moved across by p.lateral_offset, kept p.edge_margin inside
// `track` unless it is null) with its speed profile under `limits` times p.speed_scale, and the
// lap it plans.
DriverLine driver_line(const CenterLine& xy, const Track* track, const DriverProfile& p, const motion::VehicleLimits& limits);

// A closed line moved `offset` m across it (left positive), each point along its own normal.
CenterLine moved_across(const CenterLine& xy, double offset);

// The time to drive a closed line's profile, point to point in straight steps.
double planned_lap_s(const motion::RacingLine& r);

}  // namespace brickyard::sim
