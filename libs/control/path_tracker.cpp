#include "path_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::control {

void PathTracker::set_path(std::vector<PathPoint> path) {
  path_ = std::move(path);
  s_.assign(path_.size(), 0.0);
  for (std::size_t i = 1; i < path_.size(); ++i)
    s_[i] = s_[i - 1] + std::hypot(path_[i].x - path_[i - 1].x, path_[i].y - path_[i - 1].y);
  length_ = path_.empty() ? 0 : s_.back();
  // A planner's path over a horizon is open, a racing line closed: the gap between the ends tells.
  double longest = 0;
  for (std::size_t i = 1; i < path_.size(); ++i) longest = std::max(longest, s_[i] - s_[i - 1]);
  const double gap = path_.size() >= 2 ? std::hypot(path_.front().x - path_.back().x, path_.front().y - path_.back().y) : 0.0;
  closed_ = p_.closed && path_.size() >= 3 && gap <= 2 * longest;
  if (closed_) length_ += gap;
  seg_ = -1;
}

int PathTracker::segments() const {
  const int n = static_cast<int>(path_.size());
  return closed_ ? n : n - 1;
}

PathPoint PathTracker::at(double s) const {
  const int n = static_cast<int>(path_.size());
  if (closed_) s = std::fmod(std::fmod(s, length_) + length_, length_);
  else s = std::clamp(s, 0.0, length_);
  int i = static_cast<int>(std::upper_bound(s_.begin(), s_.end(), s) - s_.begin()) - 1;
  i = std::clamp(i, 0, segments() - 1);
  const PathPoint& a = path_[i];
  const PathPoint& b = path_[(i + 1) % n];
  const double seg_len = (i + 1 < n ? s_[i + 1] : length_) - s_[i];
  const double t = seg_len > 0 ? std::clamp((s - s_[i]) / seg_len, 0.0, 1.0) : 0.0;
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.speed + t * (b.speed - a.speed)};
}

PathTracker::PathTracker(TrackerParams p) : p_(p) {
  p_.lqr.delay = p_.steer_delay + p_.command_latency;
  if (p_.steer_law == SteerLaw::lqr) lqr_ = LateralLqr(p_.car, p_.lqr);
}

void PathTracker::project(double x, double y, double& s_car, double& cte) {
  const int n = static_cast<int>(path_.size()), m = segments();
  double best = 1e300;
  auto try_seg = [&](int i) {
    const PathPoint& a = path_[i];
    const PathPoint& b = path_[(i + 1) % n];
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((x - a.x) * dx + (y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
    const double px = a.x + t * dx - x, py = a.y + t * dy - y, d2 = px * px + py * py;
    if (d2 < best) {
      best = d2;
      seg_ = i;
      s_car = s_[i] + t * std::sqrt(l2);
      cte = (dx * (y - a.y) - dy * (x - a.x)) / std::max(std::sqrt(l2), 1e-9);  // left positive
    }
  };
  if (seg_ < 0) {
    for (int i = 0; i < m; ++i) try_seg(i);
  } else {
    const int from = seg_;
    for (int k = -30; k <= 30; ++k) {
      const int i = closed_ ? ((from + k) % m + m) % m : from + k;
      if (i >= 0 && i < m) try_seg(i);
    }
    if (best > 25.0)  // more than 5 m off near the last place: the car (or the path) jumped
      for (int i = 0; i < m; ++i) try_seg(i);
  }
}

void PathTracker::inside(double& lo, double& hi) const {
  // On an open path a span past an end slides back onto the path: clamped ends would meet in one
  // point, and its heading (atan2 of nothing) would read as a sharp turn.
  if (closed_) return;
  if (lo < 0) hi = std::min(hi - lo, length_), lo = 0;
  if (hi > length_) lo = std::max(lo - (hi - length_), 0.0), hi = length_;
}

double PathTracker::heading(double s) const {
  double lo = s - 1.0, hi = s + 1.0;
  inside(lo, hi);
  const PathPoint a = at(lo), b = at(hi);
  return std::atan2(b.y - a.y, b.x - a.x);
}

double PathTracker::curvature(double s) const {
  double w = std::max(p_.curvature_window, 2.0);
  double lo = s - 0.5 * w, hi = s + 0.5 * w;
  inside(lo, hi);
  w = hi - lo;
  if (w < 2.0) return 0.0;  // a path this short has no curvature to speak of
  return std::remainder(heading(hi) - heading(lo), 2 * M_PI) / w;
}

double PathTracker::speed_target(double s_car, double speed) const {
  // At most 2 km of preview: a corrupt speed must not become an endless loop.
  const double preview = std::clamp(p_.preview_time * speed, 1.0, 2000.0);
  double v_target = at(s_car).speed;
  for (double ds = 1.0; ds <= preview; ds += 1.0) {
    const double v = at(s_car + ds).speed;
    v_target = std::min(v_target, std::sqrt(v * v + 2 * p_.decel * ds));
  }
  return v_target;
}

double PathTracker::steer_pure_pursuit(const CarState& c, double s_car) const {
  const double ld = std::clamp(p_.lookahead_time * c.speed, p_.lookahead_min, p_.lookahead_max);
  const PathPoint target = at(s_car + ld);
  const double dx = target.x - c.x, dy = target.y - c.y, dist = std::max(std::hypot(dx, dy), 1e-3);
  const double alpha = std::atan2(dy, dx) - c.yaw;
  return std::atan2(2 * p_.wheelbase * std::sin(alpha), dist);
}

double PathTracker::steer_lqr(const CarState& c) {
  // The centre of gravity now: the law plans over the delay itself, with its outputs still on
  // their way to the wheels.
  const double gx = c.x + p_.car.lr * std::cos(c.yaw), gy = c.y + p_.car.lr * std::sin(c.yaw);
  double s_cog = 0, e_y = 0;
  project(gx, gy, s_cog, e_y);
  const double kappa = curvature(s_cog);
  PathErrors e;
  e.e_y = e_y;
  e.e_psi = std::remainder(c.yaw - heading(s_cog), 2 * M_PI);
  e.e_y_rate = c.speed * std::sin(e.e_psi) + c.lateral_speed;
  e.e_psi_rate = c.yaw_rate - c.speed * kappa;
  errors_ = e;
  kappa_ = kappa;
  const double v = std::max(c.speed, 1.0);
  return lqr_.steer(e, kappa, v, past_outputs(time_, lqr_.feedforward(kappa, v)));
}

std::vector<double> PathTracker::past_outputs(double t, double ff) const {
  std::vector<double> past(static_cast<std::size_t>(lqr_.memory()), 0.0);
  for (std::size_t j = 0; j < past.size(); ++j) {
    const double at = t - static_cast<double>(j + 1) * p_.lqr.period + 1e-9;
    // The output in force then: the last one sent at or before it (none yet: the feedforward's).
    auto it = std::upper_bound(outputs_.begin(), outputs_.end(), at, [](double x, const auto& o) { return x < o.first; });
    if (it != outputs_.begin()) past[j] = std::prev(it)->second - ff;
  }
  return past;
}

void PathTracker::remember(double t, double steer) {
  outputs_.emplace_back(t, steer);
  // Kept while one of them may still be in force within the law's memory.
  const double horizon = t - static_cast<double>(lqr_.memory() + 1) * p_.lqr.period;
  while (outputs_.size() > 1 && outputs_[1].first <= horizon) outputs_.pop_front();
}

void PathTracker::pedals_feedforward(double s_car, double v_target, const CarState& c, Command& out) const {
  const Powertrain& pt = p_.powertrain;
  const double v = std::max(c.speed, 0.0);
  // The target's slope half a second ahead: the acceleration the profile asks for. Its preview
  // is the car's, as the target's is: previewing at the target's speed sees a slow corner the
  // target cannot yet see, reads that as a steep slope, and brakes a slow car to a standstill.
  const double ahead = std::max(2.0, 0.5 * v);
  const double v_next = speed_target(s_car + ahead, std::max(v, 1.0));
  double a = (v_next * v_next - v_target * v_target) / (2 * ahead) + p_.accel_gain * (v_target - v);
  // Faster than the target: the error alone, never the profile's rise ahead. A car too fast in a
  // corner exit accelerated on that rise (Monza's first chicane on a mapped file: throttle at
  // 0.48, 1.7 m/s over the target, the steering at its stop) and ran wide into the wall.
  if (v > v_target) a = std::min(a, p_.accel_gain * (v_target - v));
  if (p_.grip > 0) {  // within the friction circle, less what the turn takes
    auto room = [&](double at) {
      const double lat = at * at * std::abs(curvature(s_car));
      return std::sqrt(std::max(0.0, p_.grip * p_.grip - lat * lat));
    };
    // Accelerating: what the turn leaves at the car's speed. Braking: what it leaves at the
    // target's, the budget the speed profile planned the braking with. At the car's own speed a
    // car arriving too fast had its braking cut (to the fifth of the grip below) exactly when it
    // had to slow, arrived faster still and left the line (the same chicane). Braking keeps a
    // fifth of the grip however tight the turn.
    a = std::clamp(a, -std::max(room(std::min(v, v_target)), 0.2 * p_.grip), room(v));
  }
  const double force = pt.mass * a + pt.drag * v * v + (v > 0.05 ? pt.rolling : 0.0);
  out.throttle = out.brake = 0;
  if (force >= 0) {
    const double available = std::min(pt.max_drive_force, pt.max_power / std::max(v, 1.0));
    out.throttle = std::clamp(force / std::max(available, 1.0), 0.0, 1.0);
  } else {
    out.brake = std::clamp(-force / std::max(pt.max_brake_force, 1.0), 0.0, 1.0);
  }
}

Command PathTracker::control(const CarState& car) {
  // The outputs' clock: the estimates' stamps; one that goes back (a replay started over) starts
  // the record over.
  const double t = std::isnan(car.time) ? time_ + p_.lqr.period : car.time;
  if (t < time_) outputs_.clear();
  time_ = t;
  Command c = steer_and_pedals(car);
  if (p_.steer_law == SteerLaw::lqr) remember(time_, c.steer);
  return c;
}

Command PathTracker::steer_and_pedals(const CarState& car) {
  Command c;
  if (!has_path()) {
    c.brake = 1;
    return c;
  }
  double s_car = 0;
  project(car.x, car.y, s_car, cte_);
  const double steer = p_.steer_law == SteerLaw::lqr ? steer_lqr(car) : steer_pure_pursuit(car, s_car);
  if (p_.steer_law == SteerLaw::lqr) project(car.x, car.y, s_car, cte_);  // the car's own place again
  c.steer = std::clamp(steer, -p_.max_steer, p_.max_steer);
  // Speed: brake early enough for every slower point of the preview.
  v_target_ = speed_target(s_car, car.speed);
  if (p_.pedal_law == PedalLaw::feedforward) pedals_feedforward(s_car, v_target_, car, c);
  else pedals_for(v_target_, car.speed, p_.speed_gain, c);
  c.target_speed = v_target_;
  return c;
}

}  // namespace brickyard::control
