#include "pure_pursuit.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

int PurePursuit::nearest(double x, double y) {
  const int n = static_cast<int>(line_.x.size());
  auto d2 = [&](int i) { return (line_.x[i] - x) * (line_.x[i] - x) + (line_.y[i] - y) * (line_.y[i] - y); };
  int best = 0;
  if (hint_ < 0) {
    for (int i = 1; i < n; ++i)
      if (d2(i) < d2(best)) best = i;
  } else {
    best = hint_;
    for (int k = -20; k <= 20; ++k) {
      int i = ((hint_ + k) % n + n) % n;
      if (d2(i) < d2(best)) best = i;
    }
  }
  hint_ = best;
  return best;
}

Command PurePursuit::control(double x, double y, double yaw, double speed, double* target_speed) {
  const int n = static_cast<int>(line_.x.size());
  int i = nearest(x, y);
  const double ld = std::clamp(p_.lookahead_time * speed, p_.lookahead_min, p_.lookahead_max);
  // Walk along the line to the first point at least ld away.
  int j = i;
  for (int k = 0; k < n; ++k) {
    j = (i + k) % n;
    if (std::hypot(line_.x[j] - x, line_.y[j] - y) >= ld) break;
  }
  const double dx = line_.x[j] - x, dy = line_.y[j] - y;
  const double alpha = std::atan2(dy, dx) - yaw;
  const double dist = std::hypot(dx, dy);
  Command c;
  c.steer = std::clamp(std::atan2(2 * p_.wheelbase * std::sin(alpha), dist), -p_.max_steer, p_.max_steer);
  const double v_ref = line_.speed[i];
  const double u = p_.speed_gain * (v_ref - speed);
  c.throttle = std::clamp(u, 0.0, 1.0);
  c.brake = std::clamp(-u, 0.0, 1.0);
  if (target_speed) *target_speed = v_ref;
  return c;
}

}  // namespace brickyard::sim
