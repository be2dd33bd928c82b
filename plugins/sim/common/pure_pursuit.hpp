#pragma once
// The ground-truth driver's steering: a racing line with a speed profile (libs/motion) tracked by
// pure pursuit to the nearest vertex and a proportional speed controller. It lets a graph drive
// the simulator without the car stack. Framework-free.
#include "motion/command.hpp"
#include "motion/racing_line.hpp"

#include <vector>

namespace brickyard::sim {

using motion::Command;
using motion::RacingLine;

struct PursuitParams {
  double wheelbase = 0;  // m: the vehicle description's
  double lookahead_min = 12, lookahead_time = 0.6, lookahead_max = 60;  // m, s, m
  double speed_gain = 0.5;  // throttle (or brake) per m/s of speed error
  double max_steer = 0;  // rad: the vehicle description's
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
