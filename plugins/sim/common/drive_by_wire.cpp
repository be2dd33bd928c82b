#include "drive_by_wire.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

using namespace brickyard::vehicle_interface;

namespace {

size_t command_slot(RaptorMessage m) { return raptor_index(m) - raptor_index(RaptorMessage::brake_pressure_cmd); }

}  // namespace

SimDriveByWire::SimDriveByWire(VehicleCanMapping mapping, SimDbwParams p, uint64_t seed)
    : mapping_(std::move(mapping)), p_(p), rng_(seed) {
  fresh_ns_.fill(-1);
  for (size_t i = 0; i < kRaptorCommands.size(); ++i) checkers_[i] = CounterChecker(mapping_.dbc().counter_modulus(kRaptorCommands[i]));
  for (size_t i = 0; i < kRaptorReports.size(); ++i) report_counters_[i] = CounterSender(mapping_.dbc().counter_modulus(kRaptorReports[i]));
}

void SimDriveByWire::take(const ReadFrame& r, int64_t now_ns) {
  const size_t i = command_slot(r.message);
  ++counts_.received[i];
  if (!r.counter) {  // a command without a counter (gear_shift_cmd) is fresh when it comes
    fresh_ns_[i] = now_ns;
    return;
  }
  const CounterStep step = checkers_[i].check(*r.counter);
  if (step == CounterStep::repeated) {  // a sender that is stuck: not a sign of life
    ++counts_.repeats[i];
    return;
  }
  if (step == CounterStep::skipped) ++counts_.skips[i];
  fresh_ns_[i] = now_ns;
}

void SimDriveByWire::receive(const std::vector<CanFrame>& frames, int64_t now_ns) {
  for (const CanFrame& f : frames) {
    if (lose()) {
      ++counts_.lost_in;
      continue;
    }
    ++counts_.frames_in;
    DbwSetpoint next = setpoint_;
    const std::optional<ReadFrame> r = mapping_.read_command(f, next);
    if (!r) {
      ++counts_.other_frames;
      continue;
    }
    if (!r->error.empty()) {
      ++counts_.bad_frames;
      continue;
    }
    setpoint_ = next;
    take(*r, now_ns);
  }
}

motion::Command SimDriveByWire::command(int64_t now_ns) {
  if (start_ns_ < 0) start_ns_ = now_ns;
  const auto age_s = [&](RaptorMessage m) {
    const int64_t t = fresh_ns_[command_slot(m)];
    return static_cast<double>(now_ns - (t >= 0 ? t : start_ns_)) * 1e-9;
  };
  const bool any = fresh_ns_[command_slot(RaptorMessage::steering_cmd)] >= 0;
  const double actuators = std::max({age_s(RaptorMessage::brake_pressure_cmd), age_s(RaptorMessage::accelerator_cmd),
                                     age_s(RaptorMessage::steering_cmd)});
  const bool lost = age_s(RaptorMessage::ct_report) > (any ? p_.heartbeat_timeout_s : p_.first_command_timeout_s);
  if (lost && !heartbeat_lost_) ++counts_.heartbeat_losses;
  heartbeat_lost_ = lost;
  const bool stop = lost || actuators > (any ? p_.command_timeout_s : p_.first_command_timeout_s);
  if (stop && !stopping_) ++counts_.timeouts;
  stopping_ = stop;
  const int gears = static_cast<int>(mapping_.maps().gear_ratios.size());
  if (setpoint_.gear >= 1 && setpoint_.gear <= gears) gear_ = setpoint_.gear;  // the gearbox shifts at once
  applied_ = any ? from_actuation(setpoint_.actuation, mapping_.maps()) : motion::Command{};
  if (stop) {
    applied_.throttle = 0;
    applied_.brake = p_.timeout_brake;
    if (p_.centre_steering) applied_.steer = 0;
  }
  return applied_;
}

std::vector<CanFrame> SimDriveByWire::reports(const SimCarReading& car) {
  const DbwMaps& m = mapping_.maps();
  DbwReports r;
  r.wheel_fl = std::max(car.wheel_fl, 0.0), r.wheel_fr = std::max(car.wheel_fr, 0.0);
  r.wheel_rl = std::max(car.wheel_rl, 0.0), r.wheel_rr = std::max(car.wheel_rr, 0.0);
  const Actuation applied = to_actuation(applied_, m);
  r.brake_front_kpa = r.brake_rear_kpa = applied.brake_pressure_kpa;  // one pressure: no brake bias modelled
  r.accelerator_pct = r.throttle_pct = applied.accelerator_pct;
  r.steer_motor_deg = to_actuation({car.steer, 0, 0, 0}, m).steer_motor_deg;
  r.gear = std::max(gear_, 1);
  r.engine_rpm = engine_rpm(m, r.gear, car.speed);
  r.speed = std::max(car.speed, 0.0);
  r.engine_running = r.engine_run_switch = true;
  r.gear_shift_status = 1;  // ready to shift
  r.diagnostic_bits = heartbeat_lost_ ? raptor_diagnostic_mask("adlink_hb_lost") : 0;
  std::vector<CanFrame> out;
  for (size_t i = 0; i < kRaptorReports.size(); ++i) {
    const PackResult p = mapping_.report_frame(kRaptorReports[i], r, report_counters_[i].next());
    if (!p.ok()) continue;  // cannot happen: the values are within what the signals carry or clamped
    if (lose()) {
      ++counts_.lost_out;
      continue;
    }
    out.push_back(p.frame);
  }
  return out;
}

}  // namespace brickyard::sim
