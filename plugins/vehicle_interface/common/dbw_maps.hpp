#pragma once
// The maps between the stack's ControlCommand (road-wheel angle in rad, throttle and brake 0..1) and
// what the drive-by-wire takes (steering motor angle in deg, accelerator pedal in percent, brake
// pressure in kPa, a gear), from the vehicle file (libs/vehicle: steering, drive_by_wire):
//   motor angle  = road-wheel angle x steering ratio (the ratio is motor to road wheel)
//   pedal        = throttle x 100 %
//   pressure     = brake x max_brake_pressure_kpa (linear: pressure to brake torque is a constant)
// each clamped first to the car's limits (steer to +-max_steer, pedals to 0..1), and back again for
// the simulated drive-by-wire. docs/vehicle-interface.md. Framework-free.
#include "motion/command.hpp"
#include "vehicle/vehicle.hpp"

#include <optional>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

struct DbwMaps {
  double steering_ratio = 15;          // motor deg per road-wheel deg
  double max_steer_rad = 0.35;         // road wheel
  double max_brake_pressure_kpa = 6000;
  double tyre_radius_m = 0.3;
  double final_drive = 3;
  std::vector<double> gear_ratios;     // first gear first
  double redline_rpm = 7500;
  double mass_kg = 815;                // for the brake a deceleration needs
  double max_brake_force_n = 20000;
};

// The maps of a car, or nullopt and `error` naming `file` when it has no drive_by_wire section.
std::optional<DbwMaps> dbw_maps(const vehicle::Vehicle& car, const std::string& file, std::string& error);

// What the drive-by-wire is asked for.
struct Actuation {
  double steer_motor_deg = 0;
  double accelerator_pct = 0;
  double brake_pressure_kpa = 0;
};

// "" or why a command cannot be driven (a value that is not a finite number).
std::string command_problem(const motion::Command& c);
Actuation to_actuation(const motion::Command& c, const DbwMaps& m);    // clamped to the car's limits
motion::Command from_actuation(const Actuation& a, const DbwMaps& m);  // the inverse, clamped too

// The brake pedal (0..1) that decelerates the car at `decel_mps2` by its brakes alone (drag and
// rolling resistance add to it), at most 1.
double brake_for_deceleration(const DbwMaps& m, double decel_mps2);

// The engine's speed in `gear` (1-based) at `speed_mps` (wheel speed through the tyre radius, the
// gear's ratio and the final drive); 0 for gear 0 or a gear the car lacks.
double engine_rpm(const DbwMaps& m, int gear, double speed_mps);

}  // namespace brickyard::vehicle_interface
