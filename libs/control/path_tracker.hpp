#pragma once
// Path tracking, framework-free: the car's place on a path's polyline, a steering law and a speed
// law. The control library of the car stack (control.path_tracker) and of the simulator's
// ground-truth driver (sim.truth_follower).
//  - Where the car is: its projection on the path's segments (not the nearest vertex), searched
//    near the last one.
//  - Steering, `pure_pursuit`: the point one look-ahead L = clamp(lookahead_time * v, min, max)
//    further along the path (interpolated), delta = atan(2 wheelbase sin(alpha) / L), alpha its
//    bearing from the car's heading.
//  - Steering, `lqr`: the dynamic single-track model's curvature feedforward plus LQR feedback on
//    the centre of gravity's lateral and heading errors (lateral_lqr.hpp), planned over the
//    steering's delay and the command's way to the wheels with the tracker's own outputs of that
//    time (kept by the estimate's stamps); the path's curvature taken from its geometry over
//    curvature_window metres.
//  - Speed target: the lowest path speed over the next preview_time * v metres, and the speed from
//    which the car can still brake (at `decel`) to each slower point further on within that
//    preview — so it is slow at the corner, not after it.
//  - Pedals, `proportional`: pedal = speed_gain x speed error. `feedforward`: the acceleration the
//    target's slope asks for plus accel_gain x speed error (the error alone when the car is faster
//    than the target), within the friction circle (grip less the lateral acceleration the path's
//    curvature takes: at the car's speed for drive, at the target's for braking), turned into
//    drive or brake force with the car's mass, drag and rolling resistance.
#include "lateral_lqr.hpp"
#include "motion/command.hpp"

#include <deque>
#include <limits>
#include <utility>
#include <vector>

namespace brickyard::control {

using motion::Command;
using motion::pedals_for;

struct PathPoint {
  double x, y, speed;
};

enum class SteerLaw { pure_pursuit, lqr };
enum class PedalLaw { proportional, feedforward };

// What the feedforward pedals need of the car (from its description).
struct Powertrain {
  double mass = 0;            // kg
  double max_drive_force = 0, max_power = 0, max_brake_force = 0;  // N, W, N
  double drag = 0;            // N per (m/s)^2: air density x drag area / 2
  double rolling = 0;         // N: rolling resistance x m g
};

struct TrackerParams {
  double wheelbase = 0;     // m: the vehicle description's
  double lookahead_min = 10, lookahead_time = 0.6, lookahead_max = 60;  // m, s, m
  double max_steer = 0.35;  // rad: the AV-21's for tests; apply_vehicle sets the car's
  double speed_gain = 0.5;  // pedal per m/s of error
  double preview_time = 3;  // s of path ahead the speed looks at
  double decel = 10;        // m/s^2 the car may brake at
  bool closed = true;       // the path may be a loop (a racing line): it is one when its end lies
                            // within two of its longest steps of its start
  SteerLaw steer_law = SteerLaw::pure_pursuit;
  LateralModel car;         // lqr: the vehicle description's
  LateralLqrParams lqr;
  double steer_delay = 0;   // s: the actuator's
  double command_latency = 0.05;  // s: lqr: a command's way to the actuator (manager, bus) and the estimate's age
  double curvature_window = 10;  // m
  PedalLaw pedal_law = PedalLaw::proportional;
  Powertrain powertrain;    // feedforward: the vehicle description's
  double accel_gain = 1.0;  // (m/s^2) per m/s of speed error
  double grip = 0;          // m/s^2 of combined acceleration (the friction circle); 0: unbounded
};

// What the tracker knows of the car: the base_link (rear axle) pose and its speed; the yaw rate
// and the lateral speed where known (lqr's error rates; 0 otherwise); the estimate's time (lqr's
// record of its own outputs; NaN: each call one lqr period after the last).
struct CarState {
  double x = 0, y = 0, yaw = 0, speed = 0, yaw_rate = 0, lateral_speed = 0;
  double time = std::numeric_limits<double>::quiet_NaN();
};

class PathTracker {
 public:
  explicit PathTracker(TrackerParams p = {});
  const TrackerParams& params() const { return p_; }
  // A new path; the search for the car's place starts over.
  void set_path(std::vector<PathPoint> path);
  bool has_path() const { return path_.size() >= 2; }
  // The car's state -> command. Without a path: brake, wheel straight.
  Command control(const CarState& car);
  Command control(double x, double y, double yaw, double speed) { return control(CarState{x, y, yaw, speed}); }
  // The speed the tracker aimed at in the last call, m/s.
  double target_speed() const { return v_target_; }
  // lqr: the errors and the path curvature of the last call.
  const PathErrors& errors() const { return errors_; }
  double path_curvature() const { return kappa_; }
  // Cross-track error of the last call, m (left of the path positive).
  double cross_track() const { return cte_; }

 private:
  int segments() const;
  // Point and speed at arc length s (wrapped on a closed path, clamped on an open one).
  PathPoint at(double s) const;
  // The path's heading at s (a 2 m chord) and its curvature over curvature_window.
  double heading(double s) const;
  // [lo, hi] moved onto an open path, its length kept where the path is long enough.
  void inside(double& lo, double& hi) const;
  double curvature(double s) const;
  // The nearest projection of (x, y) on a segment, near the last one once found: arc length and
  // the signed distance (left positive).
  void project(double x, double y, double& s, double& cte);
  // The speed the car should have at s: the path's, and low enough to brake for what follows.
  double speed_target(double s, double speed) const;
  double steer_pure_pursuit(const CarState& c, double s_car) const;
  Command steer_and_pedals(const CarState& car);
  double steer_lqr(const CarState& c);
  // lqr: the tracker's outputs in force 1..memory periods before t, about the feedforward ff.
  std::vector<double> past_outputs(double t, double ff) const;
  void remember(double t, double steer);
  void pedals_feedforward(double s_car, double v_target, const CarState& c, Command& out) const;
  std::vector<PathPoint> path_;
  std::vector<double> s_;  // arc length at each point
  double length_ = 0;
  int seg_ = -1;
  bool closed_ = false;  // this path
  double cte_ = 0, v_target_ = 0, kappa_ = 0;
  PathErrors errors_;
  TrackerParams p_;
  LateralLqr lqr_;  // lqr: built once, from p_
  std::deque<std::pair<double, double>> outputs_;  // lqr: (time, steering) sent, oldest first
  double time_ = 0;  // lqr: the last call's
};

}  // namespace brickyard::control
