#pragma once
// Dynamic single-track (bicycle) model of the race car: lateral tyre forces from slip angles
// (linear with saturation, or a Pacejka magic formula), drive and brake, aero drag and downforce,
// the component of gravity on a banked road, and a steering actuator with delay and rate limit.
// State at the centre of gravity; framework-free.
#include "motion/command.hpp"
#include "vehicle/vehicle.hpp"

#include <Eigen/Core>

#include <deque>
#include <string>

namespace brickyard::sim {

// The car's parameters are the shared vehicle description (libs/vehicle, one file per car).
using VehicleParams = vehicle::Vehicle;
using motion::Command;

struct CarState {
  double x = 0, y = 0, yaw = 0;  // CG, map frame
  double vx = 0, vy = 0, r = 0;  // body frame at the CG
  double steer = 0;              // road-wheel angle now
  double ax = 0, ay = 0;         // body-frame acceleration of the CG (last step)
  double fy_front = 0, fy_rear = 0;
};

class VehicleModel {
 public:
  explicit VehicleModel(VehicleParams p) : p_(std::move(p)) {}
  const VehicleParams& params() const { return p_; }
  CarState& state() { return s_; }
  const CarState& state() const { return s_; }

  // Advance by dt. `grad` is the road surface gradient (dz/dx, dz/dy) under the car.
  void step(double dt, const Command& cmd, const Eigen::Vector2d& grad);

  // Lateral force of one axle for slip angle alpha and normal load fz.
  double tyre_force(double alpha, double fz, double stiffness) const;

 private:
  VehicleParams p_;
  CarState s_;
  double t_ = 0;
  std::deque<std::pair<double, double>> steer_queue_;  // (time it takes effect, value)
  double steer_target_ = 0;
};

}  // namespace brickyard::sim
