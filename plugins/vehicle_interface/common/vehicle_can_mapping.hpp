#pragma once
// The stack's values to and from the Raptor's frames, both ways: the car's side packs commands and
// reads reports, the simulated drive-by-wire reads commands and packs reports, through the same
// DBC (RaptorDbc) and the same maps (DbwMaps). Units on the wire are the DBC's (deg, %, kPa, km/h,
// rpm); in these structs, the stack's where it has one (m/s). docs/vehicle-interface.md.
// Framework-free.
#include "dbw_maps.hpp"
#include "raptor_dbc.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace brickyard::vehicle_interface {

// What the commands carry.
struct DbwSetpoint {
  Actuation actuation;     // brake_pressure_cmd, accelerator_cmd, steering_cmd
  int gear = 0;            // gear_shift_cmd: desired_gear
  int ct_state = 0;        // ct_report: the team's state
  int vehicle_number = 0;  // ct_report: veh_num
  int track_ack = 0;       // ct_report: track_cond_ack, race control's track flag code looped back
  int vehicle_ack = 0;     // ct_report: veh_sig_ack, its vehicle flag code looped back
};

// What the reports carry.
struct DbwReports {
  double wheel_fl = 0, wheel_fr = 0, wheel_rl = 0, wheel_rr = 0;  // m/s (wheel_speed_report, km/h on the wire)
  double brake_front_kpa = 0, brake_rear_kpa = 0;                 // brake_pressure_report
  double accelerator_pct = 0;                                     // accelerator_report
  double steer_motor_deg = 0;                                     // steering_report
  double throttle_pct = 0;                                        // pt_report_1: throttle_position
  int gear = 0;                                                   // pt_report_1: current_gear
  double engine_rpm = 0;
  double speed = 0;                                               // m/s (vehicle_speed_kmph)
  bool engine_running = false, engine_run_switch = false;
  int gear_shift_status = 0;
  uint32_t diagnostic_bits = 0;                                   // bit k: raptor_diagnostic_bits()[k]
  int motec_warning = 0;
};

// A frame of one of the messages, read into a setpoint or reports: which it was and its counter.
struct ReadFrame {
  RaptorMessage message{};
  std::optional<uint32_t> counter;
  std::vector<std::string> out_of_range;
  std::string error;  // non-empty: nothing was taken from it
};

class VehicleCanMapping {
 public:
  VehicleCanMapping(RaptorDbc dbc, DbwMaps maps) : dbc_(std::move(dbc)), maps_(std::move(maps)) {}
  // "" or why the DBC's signals cannot carry what this car needs (the steering motor's angle at
  // max_steer, the brake's maximum pressure, a full pedal, the top gear).
  std::string capacity_problem(const std::string& dbc_file) const;

  const RaptorDbc& dbc() const { return dbc_; }
  const DbwMaps& maps() const { return maps_; }

  // The car's side.
  PackResult command_frame(RaptorMessage m, const DbwSetpoint& s, uint32_t counter) const;
  // A report read into `r` (only the fields of that report change); nullopt: the frame is no report.
  std::optional<ReadFrame> read_report(const CanFrame& f, DbwReports& r) const;

  // The simulated drive-by-wire's side.
  PackResult report_frame(RaptorMessage m, const DbwReports& r, uint32_t counter) const;
  // A command read into `s`; nullopt: the frame is no command.
  std::optional<ReadFrame> read_command(const CanFrame& f, DbwSetpoint& s) const;

 private:
  RaptorDbc dbc_;
  DbwMaps maps_;
};

}  // namespace brickyard::vehicle_interface
