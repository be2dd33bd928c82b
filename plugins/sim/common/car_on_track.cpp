#include "car_on_track.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace brickyard::sim {

std::string off_the_road(const Track& track, double s, double d, double half_width) {
  const Frenet f = track.at(std::fmod(std::fmod(s, track.length()) + track.length(), track.length()), d);
  const double left = track.width_left(f.seg, f.u), right = track.width_right(f.seg, f.u);
  if (d + half_width <= left && d - half_width >= -right) return {};
  char b[200];
  std::snprintf(b, sizeof b, "the car (%.2f m wide) at d = %.2f m stands off the road at s = %.1f m, which spans d = %.2f to %.2f m",
                2 * half_width, d, f.s, -right, left);
  return b;
}

void CarOnTrack::place(const Track& track, double s, double d, double speed) {
  track_ = &track;
  Frenet f = track.at(s, d);
  Eigen::Vector2d base = track.position(f);
  double yaw = track.heading(f);
  auto& st = model_.state();
  st.yaw = yaw;
  st.x = base.x() + model_.params().lr * std::cos(yaw);
  st.y = base.y() + model_.params().lr * std::sin(yaw);
  st.vx = speed;
  hint_ = f.seg;
}

void CarOnTrack::step(double dt, const Command& c) {
  const auto& s = model_.state();
  Frenet f = track_->project(s.x, s.y, hint_);
  model_.step(dt, c, track_->road_gradient(f));
  if (!std::isfinite(s.x) || !std::isfinite(s.vx)) throw std::runtime_error("vehicle state is not finite");
}

BaseLinkTruth CarOnTrack::truth() {
  const auto& s = model_.state();
  const double lr = model_.params().lr, c = std::cos(s.yaw), sn = std::sin(s.yaw);
  const double bx = s.x - lr * c, by = s.y - lr * sn;
  Frenet f = track_->project(bx, by, hint_);
  hint_ = f.seg;
  Eigen::Vector2d g = track_->road_gradient(f);
  BaseLinkTruth t;
  t.x = bx;
  t.y = by;
  t.z = track_->road_z(f);
  t.yaw = s.yaw;
  t.pitch = -std::atan(g.x() * c + g.y() * sn);
  t.roll = std::atan(-g.x() * sn + g.y() * c);
  t.vx = s.vx;
  t.vy = s.vy - lr * s.r;
  t.yaw_rate = s.r;
  t.ax = s.ax;
  t.ay = s.ay;
  t.steer = s.steer;
  t.s = f.s;
  t.d = f.d;
  return t;
}

WatchedCommand watch_command(CommandWatchdog& watchdog, double now, bool fresh, const Command& newest) {
  const bool was = watchdog.stopping();
  WatchedCommand out{watchdog.apply(now, fresh, newest), {}};
  if (watchdog.stopping() && !was)
    out.warning = "no command for " + std::to_string(now - watchdog.quiet_since()) + " s: throttle off, braking to a stop";
  if (was && !watchdog.stopping())
    out.warning = "commands again: the stack drives (the longest gap between two so far: " + std::to_string(watchdog.longest_gap(now)) + " s)";
  return out;
}

}  // namespace brickyard::sim
