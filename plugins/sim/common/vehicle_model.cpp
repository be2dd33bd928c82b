#include "vehicle_model.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

double VehicleModel::tyre_force(double alpha, double fz, double c) const {
  const double peak = p_.mu * fz;
  if (p_.tyre == "pacejka") {
    // Fy = D sin(C atan(B a - E (B a - atan(B a)))), with B C D = cornering stiffness.
    const double b = c / (p_.pacejka_c * peak);
    const double ba = b * alpha;
    return peak * std::sin(p_.pacejka_c * std::atan(ba - p_.pacejka_e * (ba - std::atan(ba))));
  }
  return std::clamp(c * alpha, -peak, peak);
}

void VehicleModel::step(double dt, const Command& cmd, const Eigen::Vector2d& grad) {
  t_ += dt;
  // Steering actuator: the command takes effect after the delay, then moves at a bounded rate.
  steer_queue_.emplace_back(t_ + p_.steer_delay, std::clamp(cmd.steer, -p_.max_steer, p_.max_steer));
  while (!steer_queue_.empty() && steer_queue_.front().first <= t_ + 1e-12) {
    steer_target_ = steer_queue_.front().second;
    steer_queue_.pop_front();
  }
  const double max_ds = p_.max_steer_rate * dt;
  s_.steer += std::clamp(steer_target_ - s_.steer, -max_ds, max_ds);

  const double m = p_.mass, g = vehicle::gravity, L = p_.lf + p_.lr;  // the model's axles, as its forces use them
  const double d = s_.steer, cd = std::cos(d), sd = std::sin(d);
  const double vx = s_.vx, vy = s_.vy, r = s_.r;
  const double cy = std::cos(s_.yaw), sy = std::sin(s_.yaw);
  // Gravity along the road plane, in body axes (small-slope form: -m g grad).
  const double gx = -g * (grad.x() * cy + grad.y() * sy);
  const double gy = -g * (-grad.x() * sy + grad.y() * cy);
  const double cos_slope = 1.0 / std::sqrt(1.0 + grad.squaredNorm());

  const double q = 0.5 * p_.air_density * vx * vx;
  const double downforce = q * p_.lift_area;
  const double fz_f = m * g * cos_slope * p_.lr / L + downforce * p_.downforce_front;
  const double fz_r = m * g * cos_slope * p_.lf / L + downforce * (1 - p_.downforce_front);

  const double throttle = std::clamp(cmd.throttle, 0.0, 1.0), brake = std::clamp(cmd.brake, 0.0, 1.0);
  const double drive = throttle * std::min(p_.max_drive_force, p_.max_power / std::max(vx, 1.0));
  const double dir = vx >= 0 ? 1.0 : -1.0;
  const double fb = brake * p_.max_brake_force * (std::abs(vx) > 0.05 ? dir : 0.0);
  const double fx_f = -fb * p_.brake_front;
  const double fx_r = drive - fb * (1 - p_.brake_front);
  const double f_drag = -dir * q * p_.drag_area - (std::abs(vx) > 0.05 ? dir * p_.rolling_resistance * m * g : 0.0);

  double ax, ay, rdot;
  if (vx < 3.0) {
    // Slow: kinematic bicycle (slip angles are ill-defined near standstill).
    double fx = fx_f * cd + fx_r + f_drag + m * gx;
    ax = fx / m;
    double beta = std::atan(p_.lr * std::tan(d) / L);
    double v = std::max(0.0, vx + ax * dt);
    s_.vx = v * std::cos(beta);
    s_.vy = v * std::sin(beta);
    s_.r = v * std::cos(beta) * std::tan(d) / L;
    s_.ax = ax;
    s_.ay = s_.r * s_.vx;
    s_.fy_front = s_.fy_rear = 0;
  } else {
    const double alpha_f = d - std::atan2(vy + p_.lf * r, vx);
    const double alpha_r = -std::atan2(vy - p_.lr * r, vx);
    const double fy_f = tyre_force(alpha_f, fz_f, p_.cornering_front);
    const double fy_r = tyre_force(alpha_r, fz_r, p_.cornering_rear);
    const double fx = fx_r + fx_f * cd - fy_f * sd + f_drag + m * gx;
    const double fy = fy_r + fy_f * cd + fx_f * sd + m * gy;
    ax = fx / m;
    ay = fy / m;
    rdot = (p_.lf * (fy_f * cd + fx_f * sd) - p_.lr * fy_r) / p_.yaw_inertia;
    // Semi-implicit Euler: velocities first, then the pose with the new velocities.
    s_.vx += (ax + r * vy) * dt;
    s_.vy += (ay - r * vx) * dt;
    s_.r += rdot * dt;
    s_.ax = ax;
    s_.ay = ay;
    s_.fy_front = fy_f;
    s_.fy_rear = fy_r;
  }
  s_.yaw += s_.r * dt;
  s_.yaw = std::remainder(s_.yaw, 2 * M_PI);
  const double c2 = std::cos(s_.yaw), s2 = std::sin(s_.yaw);
  s_.x += (s_.vx * c2 - s_.vy * s2) * dt;
  s_.y += (s_.vx * s2 + s_.vy * c2) * dt;
}

}  // namespace brickyard::sim
