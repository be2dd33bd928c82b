#include "gravity_tilt.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

void GravityTilt::trim(std::int64_t now) {
  // Two windows kept: drift() looks back one from the newest frame, which may lag the IMU.
  while (!imu_.empty() && imu_.front().t < now - 2 * window_ns_) imu_.pop_front();
  while (!frames_.empty() && frames_.front().t < now - 2 * window_ns_) frames_.pop_front();
}

void GravityTilt::add_imu(std::int64_t t_ns, double f_x, double f_y, double yaw_rate, double speed) {
  if (!std::isfinite(f_x) || !std::isfinite(f_y) || !std::isfinite(yaw_rate) || !std::isfinite(speed)) return;
  if (!imu_.empty() && t_ns <= imu_.back().t) return;  // time order
  imu_.push_back({t_ns, f_x, f_y - speed * yaw_rate, speed});
  trim(t_ns);
}

void GravityTilt::add_frame(std::int64_t t_ns, double roll, double pitch) {
  if (!std::isfinite(roll) || !std::isfinite(pitch)) return;
  if (!frames_.empty() && t_ns <= frames_.back().t) return;
  frames_.push_back({t_ns, roll, pitch});
  trim(t_ns);
}

bool GravityTilt::drift(Tilt& out, double min_speed) const {
  if (frames_.empty() || imu_.empty()) return false;
  const std::int64_t to = frames_.back().t, from = to - window_ns_;
  if (frames_.front().t > from || imu_.front().t > from) return false;  // not a whole window yet
  double roll = 0, pitch = 0;
  int n = 0;
  for (const auto& f : frames_)
    if (f.t >= from && f.t <= to) roll += f.roll, pitch += f.pitch, ++n;
  double f_x = 0, lateral = 0;
  int m = 0;
  const Imu* first = nullptr;
  const Imu* last = nullptr;
  for (const auto& s : imu_) {
    if (s.t < from || s.t > to) continue;
    if (s.speed < min_speed) return false;
    if (!first) first = &s;
    last = &s;
    f_x += s.f_x, lateral += s.lateral, ++m;
  }
  if (n == 0 || m < 2 || last->t <= first->t) return false;
  const double dv_dt = (last->speed - first->speed) / (static_cast<double>(last->t - first->t) * 1e-9);
  out.roll = roll / n - std::asin(std::clamp(lateral / m / kGravity, -1.0, 1.0));
  out.pitch = pitch / n - std::asin(std::clamp((dv_dt - f_x / m) / kGravity, -1.0, 1.0));
  return true;
}

bool GravityTilt::correction(std::int64_t t_ns, double level_time_s, Tilt& out) {
  out = {};
  const std::int64_t last = last_correction_;
  last_correction_ = t_ns;
  Tilt d;
  if (last < 0 || t_ns <= last || !drift(d)) return false;
  const double part = std::min(1.0, static_cast<double>(t_ns - last) * 1e-9 / level_time_s);
  out = {d.roll * part, d.pitch * part};
  return true;
}

}  // namespace brickyard::mapping
