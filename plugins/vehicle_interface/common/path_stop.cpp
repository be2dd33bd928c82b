#include "path_stop.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace brickyard::vehicle_interface {

double steady_yaw_rate(const control::LateralModel& car, double delta, double v) {
  const double l = car.lf + car.lr;
  if (!(l > 0)) return 0;
  const double kv = car.cornering_front > 0 && car.cornering_rear > 0
                        ? car.mass * (car.lr / car.cornering_front - car.lf / car.cornering_rear) / l
                        : 0;
  const double per_curvature = l + kv * v * v;  // delta / kappa
  return per_curvature > 0 ? v * delta / per_curvature : 0;
}

void PathStop::path(double stamp, std::vector<control::PathPoint> points) {
  if (points.size() < 2) return;
  path_ = std::move(points);
  path_stamp_ = stamp;
}

bool PathStop::begin(double now) {
  active_ = false;
  line_.clear();
  // (written so that a time that is no number fails too)
  if (path_.size() < 2 || !(now - estimate_.time <= p_.max_estimate_age_s) || !(now - path_stamp_ <= p_.max_path_age_s)) return false;
  // From the estimate's time to the trip on its own speed and yaw rate (a few hundredths of a second).
  pose_ = estimate_;
  pose_t_ = estimate_.time;
  yaw_rate_ = estimate_.yaw_rate;
  lateral_ = 0;
  move(now - estimate_.time, estimate_.speed, estimate_.yaw_rate, 0);
  pose_t_ = now;
  line_ = path_;
  if (track_) line_ = stop_line(path_, nearest_point(), *track_, p_.line, {pose_.speed, p_.decel_mps2, tracker_.params().grip});
  tracker_.set_path(line_);
  active_ = true;
  return true;
}

std::size_t PathStop::nearest_point() const {
  std::size_t nearest = 0;
  double best = 1e300;
  for (std::size_t i = 0; i < line_.size(); ++i) {
    const double d = std::hypot(line_[i].x - pose_.x, line_[i].y - pose_.y);
    if (d < best) best = d, nearest = i;
  }
  return nearest;
}

double PathStop::deceleration(double v, double least) const {
  // What meeting each speed of the path ahead takes (the stack planned them: the turns' speeds),
  // and standing end_margin_m before its end.
  double wanted = least, along = 0;
  const std::size_t from = nearest_point();
  for (std::size_t i = from + 1; i < line_.size(); ++i) {
    along += std::hypot(line_[i].x - line_[i - 1].x, line_[i].y - line_[i - 1].y);
    const double target = line_[i].speed;
    if (v > target && along > 1) wanted = std::max(wanted, (v * v - target * target) / (2 * along));
  }
  const double room = along - p_.end_margin_m;
  wanted = room > 0 ? std::max(wanted, v * v / (2 * room)) : p_.max_decel_mps2;
  wanted = std::min(wanted, std::max(least, p_.max_decel_mps2));
  const double grip = tracker_.params().grip;
  if (!(grip > 0)) return wanted;
  const double lateral = v * v * std::abs(tracker_.path_curvature());
  return std::min(wanted, std::sqrt(std::max(0.0, grip * grip - lateral * lateral)));
}

void PathStop::carry_on_gyro(double dt, double v) {
  const control::LateralModel& m = tracker_.params().car;
  const double l = m.lf + m.lr;
  // The rear tyres' share of the turn's force (m lf / L x v r) over their stiffness is their slip
  // angle; times v, the rear axle's sideways speed.
  const double sideways = l > 0 && m.cornering_rear > 0 ? -m.mass * m.lf / (l * m.cornering_rear) * v * v * gyro_ : 0;
  yaw_rate_ = gyro_;
  lateral_ = sideways + m.lr * gyro_;  // the centre of gravity's, should the gyro fall silent
  move(dt, v, gyro_, sideways);
}

void PathStop::carry(double dt, double v, double delta) {
  if (!(dt > 0)) return;
  const control::LateralModel& m = tracker_.params().car;
  if (pose_t_ + dt - gyro_stamp_ <= p_.gyro_fresh_s) {
    carry_on_gyro(dt, v);
  } else if (v > kDynamicFrom && m.mass > 0 && m.yaw_inertia > 0 && m.cornering_front > 0 && m.cornering_rear > 0) {
    // The single-track model's lateral speed and yaw rate (linear tyres), stepped in pieces short
    // against its time constant (m v / (Cf + Cr): 0.1 s at 60 m/s, 0.01 s at 5 m/s).
    const int pieces = static_cast<int>(std::ceil(dt / kPiece_s));
    const double h = dt / pieces;
    for (int k = 0; k < pieces; ++k) {
      const double fy_front = m.cornering_front * (delta - (lateral_ + m.lf * yaw_rate_) / v);
      const double fy_rear = -m.cornering_rear * (lateral_ - m.lr * yaw_rate_) / v;
      const double d_lateral = (fy_front + fy_rear) / m.mass - v * yaw_rate_;
      const double d_yaw_rate = (m.lf * fy_front - m.lr * fy_rear) / m.yaw_inertia;
      lateral_ += h * d_lateral;
      yaw_rate_ += h * d_yaw_rate;
      move(h, v, yaw_rate_, lateral_ - m.lr * yaw_rate_);  // the rear axle's sideways speed
    }
  } else {
    yaw_rate_ = steady_yaw_rate(m, delta, v);
    lateral_ = 0;
    move(dt, v, yaw_rate_, 0);
  }
  pose_.speed = v;
  pose_.yaw_rate = yaw_rate_;
  pose_t_ += dt;
}

void PathStop::move(double dt, double v, double yaw_rate, double sideways) {
  const double mid = pose_.yaw + 0.5 * yaw_rate * dt;
  pose_.x += dt * (v * std::cos(mid) - sideways * std::sin(mid));
  pose_.y += dt * (v * std::sin(mid) + sideways * std::cos(mid));
  pose_.yaw = std::remainder(pose_.yaw + yaw_rate * dt, 2 * M_PI);
}

StopCommand PathStop::step(double now, double v, double delta, double least) {
  carry(now - pose_t_, v, delta);
  pose_.time = now;
  StopCommand out;
  out.steer = tracker_.control(pose_).steer;
  out.decel = deceleration(v, std::max(least, p_.decel_mps2));
  return out;
}

}  // namespace brickyard::vehicle_interface
