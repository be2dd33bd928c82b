#include "dbw_maps.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace brickyard::vehicle_interface {

std::optional<DbwMaps> dbw_maps(const vehicle::Vehicle& car, const std::string& file, std::string& error) {
  if (!car.drive_by_wire) {
    error = file + ": /drive_by_wire: missing: the vehicle interface needs the car's brake pressure, tyre radius and gears";
    return std::nullopt;
  }
  const vehicle::DriveByWire& w = *car.drive_by_wire;
  DbwMaps m;
  m.steering_ratio = car.steering_ratio;
  m.max_steer_rad = car.max_steer;
  m.max_brake_pressure_kpa = w.max_brake_pressure_kpa;
  m.tyre_radius_m = w.tyre_radius;
  m.final_drive = w.final_drive;
  m.gear_ratios = w.gear_ratios;
  m.redline_rpm = w.redline_rpm;
  m.mass_kg = car.mass;
  m.max_brake_force_n = car.max_brake_force;
  return m;
}

std::string command_problem(const motion::Command& c) {
  if (!std::isfinite(c.steer)) return "steer is not a finite number";
  if (!std::isfinite(c.throttle)) return "throttle is not a finite number";
  if (!std::isfinite(c.brake)) return "brake is not a finite number";
  return "";
}

Actuation to_actuation(const motion::Command& c, const DbwMaps& m) {
  Actuation a;
  const double steer = std::clamp(c.steer, -m.max_steer_rad, m.max_steer_rad);
  a.steer_motor_deg = steer * 180.0 / std::numbers::pi * m.steering_ratio;
  a.accelerator_pct = std::clamp(c.throttle, 0.0, 1.0) * 100.0;
  a.brake_pressure_kpa = std::clamp(c.brake, 0.0, 1.0) * m.max_brake_pressure_kpa;
  return a;
}

motion::Command from_actuation(const Actuation& a, const DbwMaps& m) {
  motion::Command c;
  c.steer = std::clamp(a.steer_motor_deg / m.steering_ratio * std::numbers::pi / 180.0, -m.max_steer_rad, m.max_steer_rad);
  c.throttle = std::clamp(a.accelerator_pct / 100.0, 0.0, 1.0);
  c.brake = std::clamp(a.brake_pressure_kpa / m.max_brake_pressure_kpa, 0.0, 1.0);
  return c;
}

double brake_for_deceleration(const DbwMaps& m, double decel_mps2) {
  return std::clamp(decel_mps2 * m.mass_kg / m.max_brake_force_n, 0.0, 1.0);
}

double engine_rpm(const DbwMaps& m, int gear, double speed_mps) {
  if (gear < 1 || gear > static_cast<int>(m.gear_ratios.size())) return 0;
  const double wheel_rad_s = std::max(speed_mps, 0.0) / m.tyre_radius_m;
  return wheel_rad_s * m.gear_ratios[static_cast<size_t>(gear - 1)] * m.final_drive * 60.0 / (2 * std::numbers::pi);
}

}  // namespace brickyard::vehicle_interface
