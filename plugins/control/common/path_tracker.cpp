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

Command PathTracker::control(double x, double y, double yaw, double speed) {
  Command c;
  if (!has_path()) {
    c.brake = 1;
    return c;
  }
  const int n = static_cast<int>(path_.size()), m = segments();
  // The car's place: the nearest projection on a segment, near the last one once found.
  double best = 1e300, s_car = 0;
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
      cte_ = (dx * (y - a.y) - dy * (x - a.x)) / std::max(std::sqrt(l2), 1e-9);  // left positive
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
  // Steering: pure pursuit on the interpolated look-ahead point.
  const double ld = std::clamp(p_.lookahead_time * speed, p_.lookahead_min, p_.lookahead_max);
  const PathPoint target = at(s_car + ld);
  const double dx = target.x - x, dy = target.y - y, dist = std::max(std::hypot(dx, dy), 1e-3);
  const double alpha = std::atan2(dy, dx) - yaw;
  c.steer = std::clamp(std::atan2(2 * p_.wheelbase * std::sin(alpha), dist), -p_.max_steer, p_.max_steer);
  // Speed: brake early enough for every slower point of the preview.
  // At most 2 km of preview: a corrupt speed must not become an endless loop.
  const double preview = std::clamp(p_.preview_time * speed, 1.0, 2000.0);
  double v_target = at(s_car).speed;
  for (double ds = 1.0; ds <= preview; ds += 1.0) {
    const double v = at(s_car + ds).speed;
    v_target = std::min(v_target, std::sqrt(v * v + 2 * p_.decel * ds));
  }
  pedals_for(v_target, speed, p_.speed_gain, c);
  return c;
}

}  // namespace brickyard::control
