#include "gear_shifter.hpp"

#include <algorithm>
#include <cstdio>

namespace brickyard::vehicle_interface {

ShiftProblem shift_problem(const ShiftParams& p, const DbwMaps& m) {
  const int gears = static_cast<int>(m.gear_ratios.size());
  char why[200];
  if (p.fixed_gear > gears) {
    std::snprintf(why, sizeof why, "gear %d: the car has %d gears", p.fixed_gear, gears);
    return {"fixed_gear", why};
  }
  if (p.fixed_gear > 0) return {};
  if (p.up_rpm > m.redline_rpm) {
    std::snprintf(why, sizeof why, "%g rpm is above the redline, %g rpm", p.up_rpm, m.redline_rpm);
    return {"shift_up_rpm", why};
  }
  double landing = p.up_rpm;  // where the tightest upshift lands
  for (int g = 1; g < gears; ++g) landing = std::min(landing, p.up_rpm * m.gear_ratios[g] / m.gear_ratios[g - 1]);
  if (gears > 1 && p.down_rpm >= landing) {
    std::snprintf(why, sizeof why, "%g rpm must be below %.0f rpm, where an upshift at %g rpm lands", p.down_rpm, landing,
                  p.up_rpm);
    return {"shift_down_rpm", why};
  }
  return {};
}

int GearShifter::starting_gear(double speed_mps) const {
  const int gears = static_cast<int>(m_.gear_ratios.size());
  if (p_.fixed_gear > 0) return p_.fixed_gear;
  for (int g = 1; g <= gears; ++g)
    if (engine_rpm(m_, g, speed_mps) <= p_.up_rpm) return g;
  return gears;
}

int GearShifter::update(double now_s, int engaged, double rpm, double speed_mps) {
  const int gears = static_cast<int>(m_.gear_ratios.size());
  const bool known = engaged >= 1 && engaged <= gears;
  if (p_.fixed_gear > 0) return desired_ = p_.fixed_gear;
  if (desired_ == 0) return desired_ = known ? engaged : starting_gear(speed_mps);
  if (now_s - last_shift_s_ < p_.min_interval_s) return desired_;
  const int g = known ? engaged : desired_;
  if (rpm < 0 || !known) rpm = engine_rpm(m_, g, speed_mps);
  int want = g;
  if (rpm > p_.up_rpm && g < gears) {
    want = g + 1;
  } else if (rpm < p_.down_rpm && g > 1 && rpm * m_.gear_ratios[g - 2] / m_.gear_ratios[g - 1] < p_.up_rpm) {
    want = g - 1;
  }
  if (want != desired_) {
    desired_ = want;
    last_shift_s_ = now_s;
    ++shifts_;
  }
  return desired_;
}

}  // namespace brickyard::vehicle_interface
