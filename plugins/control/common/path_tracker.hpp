#pragma once
// Path tracking, framework-free: pure pursuit on a path's polyline with a speed-scheduled
// look-ahead, and speed control that brakes ahead of a slower stretch.
//  - Where the car is: its projection on the path's segments (not the nearest vertex), searched
//    near the last one.
//  - Steering: the point one look-ahead L = clamp(lookahead_time * v, min, max) further along the
//    path (interpolated), δ = atan(2 wheelbase sin α / L), α its bearing from the car's heading.
//  - Speed: the lowest path speed over the next preview_time * v metres, and the speed from which
//    the car can still brake (at `decel`) to each slower point further on within that preview —
//    so it is slow at the corner, not after it. Pedals proportional to the speed error.
#include "motion/command.hpp"

#include <vector>

namespace brickyard::control {

using motion::Command;
using motion::pedals_for;

struct PathPoint {
  double x, y, speed;
};

struct TrackerParams {
  double wheelbase = 0;     // m: the vehicle description's
  double lookahead_min = 10, lookahead_time = 0.6, lookahead_max = 60;  // m, s, m
  double max_steer = 0.35;  // rad
  double speed_gain = 0.5;  // pedal per m/s of error
  double preview_time = 3;  // s of path ahead the speed looks at
  double decel = 10;        // m/s^2 the car may brake at
  bool closed = true;       // the path may be a loop (a racing line): it is one when its end lies
                            // within two of its longest steps of its start
};

class PathTracker {
 public:
  explicit PathTracker(TrackerParams p = {}) : p_(p) {}
  const TrackerParams& params() const { return p_; }
  // A new path; the search for the car's place starts over.
  void set_path(std::vector<PathPoint> path);
  bool has_path() const { return path_.size() >= 2; }
  // base_link pose (rear axle) and speed -> command. Without a path: brake, wheel straight.
  Command control(double x, double y, double yaw, double speed);
  // Cross-track error of the last call, m (left of the path positive).
  double cross_track() const { return cte_; }

 private:
  int segments() const;
  // Point and speed at arc length s (wrapped on a closed path, clamped on an open one).
  PathPoint at(double s) const;
  std::vector<PathPoint> path_;
  std::vector<double> s_;  // arc length at each point
  double length_ = 0;
  int seg_ = -1;
  bool closed_ = false;  // this path
  double cte_ = 0;
  TrackerParams p_;
};

}  // namespace brickyard::control
