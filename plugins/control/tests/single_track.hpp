#pragma once
// The lateral law's tests' car: the AV-21's single-track model from its vehicle file, and the
// linear single-track model itself (linear tyres, no actuator) at constant speed.
#include "control/lateral_lqr.hpp"

#include "av21.hpp"

#include <cmath>

namespace brickyard::control::test_car {

inline LateralModel av21_model() {
  const auto v = av21_vehicle();
  return {v.mass, v.yaw_inertia, v.lf, v.lr, v.cornering_front, v.cornering_rear};
}

// The centre of gravity's pose and body velocities, integrated by dt at speed v with the road
// wheels at delta.
struct Bicycle {
  LateralModel m;
  double x = 0, y = 0, yaw = 0, vy = 0, r = 0;
  void step(double delta, double v, double dt) {
    const double af = delta - std::atan2(vy + m.lf * r, v), ar = -std::atan2(vy - m.lr * r, v);
    const double fyf = m.cornering_front * af, fyr = m.cornering_rear * ar;
    vy += ((fyf + fyr) / m.mass - r * v) * dt;
    r += (m.lf * fyf - m.lr * fyr) / m.yaw_inertia * dt;
    yaw += r * dt;
    x += (v * std::cos(yaw) - vy * std::sin(yaw)) * dt;
    y += (v * std::sin(yaw) + vy * std::cos(yaw)) * dt;
  }
};

}  // namespace brickyard::control::test_car
