#include "vehicle_can_mapping.hpp"

#include "can_signal.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace brickyard::vehicle_interface {

namespace {

constexpr double kKmhPerMps = 3.6;

bool is_command(RaptorMessage m) { return raptor_index(m) <= raptor_index(RaptorMessage::ct_report); }

ReadFrame read_header(const RaptorFrame& f) {
  ReadFrame r;
  r.message = f.message;
  r.counter = f.counter;
  r.out_of_range = f.out_of_range;
  r.error = f.error;
  return r;
}

void take_report(const RaptorFrame& f, DbwReports& r) {
  const SignalValues& v = f.values;
  switch (f.message) {
    case RaptorMessage::wheel_speed_report:
      r.wheel_fl = v.at("wheel_speed_FL") / kKmhPerMps, r.wheel_fr = v.at("wheel_speed_FR") / kKmhPerMps;
      r.wheel_rl = v.at("wheel_speed_RL") / kKmhPerMps, r.wheel_rr = v.at("wheel_speed_RR") / kKmhPerMps;
      break;
    case RaptorMessage::brake_pressure_report:
      r.brake_front_kpa = v.at("brake_pressure_fdbk_front"), r.brake_rear_kpa = v.at("brake_pressure_fdbk_rear");
      break;
    case RaptorMessage::accelerator_report: r.accelerator_pct = v.at("acc_pedal_fdbk"); break;
    case RaptorMessage::steering_report: r.steer_motor_deg = v.at("steering_motor_ang_avg_fdbk"); break;
    case RaptorMessage::pt_report_1:
      r.throttle_pct = v.at("throttle_position"), r.gear = static_cast<int>(v.at("current_gear"));
      r.engine_rpm = v.at("engine_speed_rpm"), r.speed = v.at("vehicle_speed_kmph") / kKmhPerMps;
      r.engine_run_switch = v.at("engine_run_switch") != 0, r.engine_running = v.at("engine_state") != 0;
      r.gear_shift_status = static_cast<int>(v.at("gear_shift_status"));
      break;
    case RaptorMessage::diagnostic_report: {
      r.diagnostic_bits = 0;
      const auto& bits = raptor_diagnostic_bits();
      for (size_t k = 0; k < bits.size(); ++k)
        if (v.at(bits[k]) != 0) r.diagnostic_bits |= 1u << k;
      r.motec_warning = static_cast<int>(v.at("motec_warning"));
      break;
    }
    default: break;
  }
}

SignalValues report_values(RaptorMessage m, const DbwReports& r) {
  switch (m) {
    case RaptorMessage::wheel_speed_report:
      return {{"wheel_speed_FL", r.wheel_fl * kKmhPerMps}, {"wheel_speed_FR", r.wheel_fr * kKmhPerMps},
              {"wheel_speed_RL", r.wheel_rl * kKmhPerMps}, {"wheel_speed_RR", r.wheel_rr * kKmhPerMps}};
    case RaptorMessage::brake_pressure_report:
      return {{"brake_pressure_fdbk_front", r.brake_front_kpa}, {"brake_pressure_fdbk_rear", r.brake_rear_kpa}};
    case RaptorMessage::accelerator_report: return {{"acc_pedal_fdbk", r.accelerator_pct}};
    case RaptorMessage::steering_report: return {{"steering_motor_ang_avg_fdbk", r.steer_motor_deg}};
    case RaptorMessage::pt_report_1:
      return {{"throttle_position", r.throttle_pct}, {"current_gear", r.gear}, {"engine_speed_rpm", r.engine_rpm},
              {"vehicle_speed_kmph", r.speed * kKmhPerMps}, {"engine_run_switch", r.engine_run_switch ? 1 : 0},
              {"engine_state", r.engine_running ? 1 : 0}, {"gear_shift_status", r.gear_shift_status}};
    case RaptorMessage::diagnostic_report: {
      SignalValues v{{"motec_warning", r.motec_warning}};
      const auto& bits = raptor_diagnostic_bits();
      for (size_t k = 0; k < bits.size(); ++k) v[bits[k]] = (r.diagnostic_bits >> k) & 1u;
      return v;
    }
    default: return {};
  }
}

SignalValues command_values(RaptorMessage m, const DbwSetpoint& s) {
  switch (m) {
    case RaptorMessage::brake_pressure_cmd: return {{"brake_pressure_cmd", s.actuation.brake_pressure_kpa}};
    case RaptorMessage::accelerator_cmd: return {{"acc_pedal_cmd", s.actuation.accelerator_pct}};
    case RaptorMessage::steering_cmd: return {{"steering_motor_ang_cmd", s.actuation.steer_motor_deg}};
    case RaptorMessage::gear_shift_cmd: return {{"desired_gear", s.gear}};
    case RaptorMessage::ct_report:  // race control's flags looped back (docs/race-control.md)
      return {{"ct_state", s.ct_state}, {"veh_num", s.vehicle_number}, {"track_cond_ack", s.track_ack}, {"veh_sig_ack", s.vehicle_ack}};
    default: return {};
  }
}

void take_command(const RaptorFrame& f, DbwSetpoint& s) {
  const SignalValues& v = f.values;
  switch (f.message) {
    case RaptorMessage::brake_pressure_cmd: s.actuation.brake_pressure_kpa = v.at("brake_pressure_cmd"); break;
    case RaptorMessage::accelerator_cmd: s.actuation.accelerator_pct = v.at("acc_pedal_cmd"); break;
    case RaptorMessage::steering_cmd: s.actuation.steer_motor_deg = v.at("steering_motor_ang_cmd"); break;
    case RaptorMessage::gear_shift_cmd: s.gear = static_cast<int>(v.at("desired_gear")); break;
    case RaptorMessage::ct_report:
      s.ct_state = static_cast<int>(v.at("ct_state")), s.vehicle_number = static_cast<int>(v.at("veh_num"));
      s.track_ack = static_cast<int>(v.at("track_cond_ack")), s.vehicle_ack = static_cast<int>(v.at("veh_sig_ack"));
      break;
    default: break;
  }
}

// The largest physical value `s` carries (its raw range through its factor and offset).
double carries_up_to(const DbcSignal& s) {
  const std::optional<RawRange> r = raw_range(s);
  if (!r) return -INFINITY;
  return std::max(r->lowest * s.factor, r->highest * s.factor) + s.offset;
}

}  // namespace

std::string VehicleCanMapping::capacity_problem(const std::string& file) const {
  const double motor = maps_.max_steer_rad * 180 / std::numbers::pi * maps_.steering_ratio;
  struct Need {
    RaptorMessage m;
    const char* signal;
    double value;
    const char* what;
  };
  const Need needs[] = {
      {RaptorMessage::steering_cmd, "steering_motor_ang_cmd", motor, "deg: max_steer x the steering ratio"},
      {RaptorMessage::brake_pressure_cmd, "brake_pressure_cmd", maps_.max_brake_pressure_kpa, "kPa: max_brake_pressure_kpa"},
      {RaptorMessage::accelerator_cmd, "acc_pedal_cmd", 100, "%: a full pedal"},
      {RaptorMessage::gear_shift_cmd, "desired_gear", static_cast<double>(maps_.gear_ratios.size()), ": the top gear"}};
  for (const Need& n : needs) {
    const DbcSignal& s = dbc_.signal(n.m, n.signal);
    const double most = carries_up_to(s);
    if (most < n.value - 1e-9) {
      char why[256];
      std::snprintf(why, sizeof why, "%s:%d: signal %s carries at most %g, the car needs %g %s", file.c_str(), s.line, n.signal,
                    most, n.value, n.what);
      return why;
    }
  }
  return "";
}

PackResult VehicleCanMapping::command_frame(RaptorMessage m, const DbwSetpoint& s, uint32_t counter) const {
  return dbc_.pack(m, command_values(m, s), counter);
}

PackResult VehicleCanMapping::report_frame(RaptorMessage m, const DbwReports& r, uint32_t counter) const {
  return dbc_.pack(m, report_values(m, r), counter);
}

std::optional<ReadFrame> VehicleCanMapping::read_report(const CanFrame& f, DbwReports& r) const {
  const std::optional<RaptorFrame> u = dbc_.unpack(f);
  if (!u || is_command(u->message)) return std::nullopt;
  if (u->error.empty()) take_report(*u, r);
  return read_header(*u);
}

std::optional<ReadFrame> VehicleCanMapping::read_command(const CanFrame& f, DbwSetpoint& s) const {
  const std::optional<RaptorFrame> u = dbc_.unpack(f);
  if (!u || !is_command(u->message)) return std::nullopt;
  if (u->error.empty()) take_command(*u, s);
  return read_header(*u);
}

}  // namespace brickyard::vehicle_interface
