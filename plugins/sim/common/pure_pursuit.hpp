#pragma once
// A ground-truth follower: a racing line with a speed profile (lateral and longitudinal
// acceleration limits) tracked by pure pursuit steering and a proportional speed controller.
// It lets a graph drive the simulator before the real stack exists. Framework-free.
#include "track.hpp"
#include "vehicle_model.hpp"

#include <vector>

namespace brickyard::sim {

struct SpeedLimits {
  double v_max = 80;       // m/s
  double a_lat = 18;       // m/s^2, lateral
  double a_accel = 8;      // m/s^2
  double a_decel = 12;     // m/s^2
};

struct RacingLine {
  std::vector<double> x, y, s, kappa, speed;
  double length = 0;
};

// Pull the line's points toward the centre line where they come closer than `margin` to a track
// edge (the racing line's files put the car's centre up to 0.6 m from the edge on IMS).
CenterLine keep_inside(const CenterLine& line, const Track& track, double margin);

// Speed profile by the usual forward/backward passes over the curvature-limited speeds (closed loop).
RacingLine make_racing_line(const CenterLine& xy, const SpeedLimits& lim, double curvature_smooth_m = 30);

struct PursuitParams {
  double wheelbase = 2.97;
  double lookahead_min = 12, lookahead_time = 0.6, lookahead_max = 60;  // m, s, m
  double speed_gain = 0.5;  // throttle (or brake) per m/s of speed error
  double max_steer = 0.35;
};

class PurePursuit {
 public:
  PurePursuit(RacingLine line, PursuitParams p) : line_(std::move(line)), p_(p) {}
  const RacingLine& line() const { return line_; }
  // base_link (rear-axle) pose and speed -> command; target speed in the result.
  Command control(double x, double y, double yaw, double speed, double* target_speed = nullptr);

 private:
  int nearest(double x, double y);
  RacingLine line_;
  PursuitParams p_;
  int hint_ = -1;
};

}  // namespace brickyard::sim
