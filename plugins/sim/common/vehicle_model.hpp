#pragma once
// Dynamic single-track (bicycle) model of the race car: lateral tyre forces from slip angles
// (linear with saturation, or a Pacejka magic formula), drive and brake, aero drag and downforce,
// the component of gravity on a banked road, and a steering actuator with delay and rate limit.
// State at the centre of gravity; framework-free.
#include <Eigen/Core>

#include <deque>
#include <string>

namespace brickyard::sim {

struct VehicleParams {
  double mass = 815;             // kg (AV-21 sim)
  double yaw_inertia = 800;      // kg m^2
  double lf = 1.68, lr = 1.29;   // m, CG to front / rear axle
  double track_width = 1.64;     // m, for wheel speeds
  double steering_ratio = 15;    // hand wheel : road wheel
  double max_steer = 0.35;       // rad, road wheel
  double max_steer_rate = 0.6;   // rad/s, road wheel
  double steer_delay = 0.02;     // s
  std::string tyre = "linear";   // linear | pacejka
  double cornering_front = 200e3, cornering_rear = 250e3;  // N/rad
  double mu = 1.6;               // friction coefficient
  double pacejka_c = 1.4, pacejka_e = -0.5;  // shape; B follows from the cornering stiffness
  double drag_area = 0.85;       // Cd * A, m^2
  double lift_area = 1.7;        // Cl * A (downforce), m^2
  double downforce_front = 0.45; // share on the front axle
  double air_density = 1.2;      // kg/m^3
  double max_power = 370e3;      // W at the rear wheels
  double max_drive_force = 9000; // N
  double max_brake_force = 20e3; // N, all four wheels
  double brake_front = 0.6;      // share of braking on the front axle
  double rolling_resistance = 0.015;
  double gravity = 9.81;
  double wheelbase() const { return lf + lr; }
};

struct Command {
  double steer = 0;     // road-wheel angle requested, rad
  double throttle = 0;  // 0..1
  double brake = 0;     // 0..1
};

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
