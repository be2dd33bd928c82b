#include "wall_follower.hpp"

#include "math/polynomial.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::control {

using math::poly_value;

void WallFollower::engage(double t, double speed) {
  t0_ = t;
  v0_ = std::max(speed, p_.restart_speed);
}

double WallFollower::steering(const WallView& wall, double speed) const {
  const double k = p_.schedule_above > 0 && speed > p_.schedule_above ? p_.schedule_above / speed : 1.0;
  const double d_w = poly_value(wall.coefficients, 0.0, 0), slope = poly_value(wall.coefficients, p_.lookahead / k, 1);
  return p_.w_theta * k * slope + p_.w_d * k * k * (d_w - p_.side * p_.gap);
}

Command WallFollower::control(double t, const WallView& wall, double speed) const {
  Command c;
  const double u = wall.valid && !wall.coefficients.empty() ? steering(wall, speed) : NAN;
  if (!std::isfinite(u)) {  // no wall, or a malformed one
    c.brake = 1;
    return c;
  }
  c.steer = std::clamp(u, -p_.max_steer, p_.max_steer);
  double target = v0_;
  if (p_.reduce_speed) target = std::max(std::min(v0_, p_.fallback_speed), v0_ - p_.decel * std::max(t - t0_, 0.0));
  // Never faster than the wall's bend allows: a line gap inside it is tighter still.
  const double d1 = poly_value(wall.coefficients, p_.lookahead, 1), d2 = poly_value(wall.coefficients, p_.lookahead, 2);
  const double kappa = std::abs(d2) / std::pow(1 + d1 * d1, 1.5);
  if (p_.a_lat > 0 && kappa > 1e-6) target = std::min(target, std::sqrt(p_.a_lat / kappa));
  pedals_for(target, speed, p_.speed_gain, c);
  return c;
}

}  // namespace brickyard::control
