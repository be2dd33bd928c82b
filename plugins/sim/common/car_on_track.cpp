#include "car_on_track.hpp"

#include <nlohmann/json.hpp>

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

std::string start_inside(const StartPlace& ours, const StartPlace& other, double front, double rear, double half_width, double length) {
  double ahead = ours.s - other.s;  // how far our base_link is ahead of the other's
  if (length > 0) ahead = std::remainder(ahead, length);
  const bool along = ahead < front + rear && -ahead < front + rear;
  const bool across = std::abs(ours.d - other.d) < 2 * half_width;
  if (!along || !across) return {};
  char b[200];
  std::snprintf(b, sizeof b, "the car at s = %.1f m, d = %.2f m stands inside the one starting at s = %.1f m, d = %.2f m (%.2f m long, %.2f m wide)",
                ours.s, ours.d, other.s, other.d, front + rear, 2 * half_width);
  return b;
}

std::vector<StartPlace> parse_starts(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_array()) throw std::invalid_argument("not a JSON array of [s, d] pairs");
  std::vector<StartPlace> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto& e = j[i];
    const std::string at = "/" + std::to_string(i);
    if (!e.is_array() || e.size() != 2) throw std::invalid_argument(at + ": not an [s, d] pair");
    for (std::size_t k = 0; k < 2; ++k)
      if (!e[k].is_number() || !std::isfinite(e[k].get<double>())) throw std::invalid_argument(at + "/" + std::to_string(k) + ": not a finite number");
    out.push_back({e[0].get<double>(), e[1].get<double>()});
  }
  return out;
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
