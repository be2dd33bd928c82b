#pragma once
// A racing line as the stack drives it: points, arc length, curvature averaged along the line and
// a speed profile; and the step that keeps a line's points inside a track's edges.
// Framework-free: the planners, brickyard-plan and the simulator's ground-truth driver use it.
#include "speed_profile.hpp"

#include "track/centre_line.hpp"
#include "track/track.hpp"

#include <string>
#include <vector>

namespace brickyard::motion {

struct RacingLine {
  std::vector<double> x, y, s, kappa, speed;
  double length = 0;
};

// Pull the line's points toward the centre line where they come closer than `margin` to a track
// edge (the racing line's files put the car's centre up to 0.6 m from the edge on IMS).
track::CenterLine keep_inside(const track::CenterLine& line, const track::Track& track, double margin);

// The first point of `line` outside the track's edges, described ("point 12 (x, y) is 3.20 m
// beyond the track's left edge at s = 410.0 m"); empty when every point is on the track.
std::string leaves_track(const track::CenterLine& line, const track::Track& track);

// The closed line with its arc length, its curvature averaged over curvature_smooth_m
// (track::signed_curvature) and speed_profile(lim) over it.
RacingLine make_racing_line(const track::CenterLine& xy, const VehicleLimits& lim, double curvature_smooth_m = 30);

// The limits a racing line has always been driven with: lateral and longitudinal acceleration
// each on its own (no ellipse, drag or power), v_max and the three accelerations as given.
VehicleLimits independent_limits(double v_max, double a_lat, double a_accel, double a_decel);

}  // namespace brickyard::motion
