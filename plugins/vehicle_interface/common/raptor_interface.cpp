#include "raptor_interface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace brickyard::vehicle_interface {

namespace {

constexpr uint64_t kProblemsSaid = 20;  // then only counted

std::array<uint32_t, kRaptorReports.size()> report_moduli(const RaptorDbc& dbc) {
  std::array<uint32_t, kRaptorReports.size()> m{};
  for (size_t i = 0; i < m.size(); ++i) m[i] = dbc.counter_modulus(kRaptorReports[i]);
  return m;
}

// "commands: ACTIVE -> STOPPING: stale for 0.1 s, braking at 6 m/s^2", and the handover's distance and time.
std::string state_change(DbwState from, const DbwWatchdog& w) {
  std::string text = std::string("commands: ") + dbw_state_name(from) + " -> " + dbw_state_name(w.state());
  char more[160] = "";
  if (w.state() == DbwState::stopping)
    std::snprintf(more, sizeof more, ": none fresh, braking to a stop (at most %.1f s before the heartbeat stops)", w.stop_bound_s());
  else if (w.state() == DbwState::handed_over)
    std::snprintf(more, sizeof more, ": stopped in %.1f m and %.2f s; ct_report's heartbeat stops", w.stop_distance_m(), w.stop_time_s());
  return text + more;
}

}  // namespace

RaptorInterface::RaptorInterface(VehicleCanMapping mapping, RaptorInterfaceParams p, std::optional<RaceControlDbc> race)
    : mapping_(std::move(mapping)),
      p_(p),
      watchdog_(p.watchdog, brake_for_deceleration(mapping_.maps(), p.watchdog.stop_decel_mps2)),
      shifter_(p.shift, mapping_.maps()),
      monitor_(static_cast<int64_t>(std::llround(p.report_timeout_s * 1e9)), report_moduli(mapping_.dbc())),
      race_dbc_(std::move(race)),
      race_(p.race_control, race_dbc_ ? race_dbc_->heartbeat_modulus() : 16) {
  for (size_t i = 0; i < kRaptorCommands.size(); ++i) {
    counters_[i] = CounterSender(mapping_.dbc().counter_modulus(kRaptorCommands[i]));
    period_ns_[i] = static_cast<int64_t>(std::llround(1e9 / p.rates_hz[i]));
  }
  setpoint_.ct_state = p.ct_state;
  setpoint_.vehicle_number = p.vehicle_number;
}

std::string RaptorInterface::command(const motion::Command& c) {
  ++counts_.commands;
  if (std::string why = command_problem(c); !why.empty()) {
    ++counts_.bad_commands;
    return why;
  }
  newest_ = c;
  fresh_ = true;
  return "";
}

std::vector<std::string> RaptorInterface::receive(const std::vector<CanFrame>& frames, int64_t now_ns) {
  std::vector<std::string> said;
  auto say = [&](std::string what) {
    if (!what.empty() && problems_said_ < kProblemsSaid) ++problems_said_, said.push_back(std::move(what));
  };
  for (const CanFrame& f : frames) {
    if (race_frame(f, now_ns, say)) continue;
    const std::optional<ReadFrame> r = mapping_.read_report(f, reports_);
    if (!r) {
      ++counts_.other_frames;
      continue;
    }
    if (!r->error.empty() || !r->out_of_range.empty()) {
      ++counts_.bad_reports;
      monitor_.bad_frame(r->message);
      say(std::string(raptor_name(r->message)) + ": " + (r->error.empty() ? "out of range: " + r->out_of_range.front() : r->error));
      if (!r->error.empty()) continue;
    }
    say(monitor_.received(r->message, now_ns, r->counter));
  }
  return said;
}

bool RaptorInterface::race_frame(const CanFrame& f, int64_t now_ns, const std::function<void(std::string)>& say) {
  if (!race_dbc_ || !race_dbc_->is_summary(f)) return false;
  const RaceSummaryRead r = race_dbc_->read(f);
  if (!r.error.empty() || !r.out_of_range.empty()) {
    ++counts_.bad_reports;
    race_.bad_frame();
    say(std::string("base_to_car_summary: ") + (r.error.empty() ? "out of range: " + r.out_of_range.front() : r.error));
    if (!r.error.empty()) return true;
  }
  if (std::string note = race_.received(r.summary, now_ns); !note.empty()) race_notes_.push_back(std::move(note));
  race_read_ = true;
  return true;
}

bool RaptorInterface::fresh_report(RaptorMessage m, int64_t now_ns) const {
  const std::optional<int64_t> t = monitor_.last_heard(m);
  return t && now_ns - *t <= static_cast<int64_t>(std::llround(p_.report_timeout_s * 1e9));
}

std::optional<double> RaptorInterface::speed(int64_t now_ns) const {
  if (fresh_report(RaptorMessage::wheel_speed_report, now_ns))
    return (reports_.wheel_fl + reports_.wheel_fr + reports_.wheel_rl + reports_.wheel_rr) / 4;
  if (fresh_report(RaptorMessage::pt_report_1, now_ns)) return reports_.speed;
  return std::nullopt;
}

void RaptorInterface::send_due(int64_t now_ns, bool heartbeat, InterfaceStep& out) {
  for (size_t i = 0; i < kRaptorCommands.size(); ++i) {
    if (!started_) next_due_ns_[i] = now_ns;
    if (now_ns < next_due_ns_[i]) continue;
    // On time, or one period from now after a step that came late: never a burst to catch up.
    next_due_ns_[i] = now_ns - next_due_ns_[i] >= period_ns_[i] ? now_ns + period_ns_[i] : next_due_ns_[i] + period_ns_[i];
    const RaptorMessage m = kRaptorCommands[i];
    if (m == RaptorMessage::ct_report && !heartbeat) continue;
    const PackResult packed = mapping_.command_frame(m, setpoint_, counters_[i].next());
    if (!packed.ok()) continue;  // cannot happen for the values the maps give: make() checked the signals
    counts_.clamped += packed.clamped.size();
    counts_.heartbeats += m == RaptorMessage::ct_report;
    out.frames.push_back(packed.frame);
  }
  started_ = true;
  counts_.frames_sent += out.frames.size();
}

void RaptorInterface::steer_stop(double now_s, int64_t now_ns, WatchdogOutput& w, std::optional<double> v) {
  if (w.state != DbwState::stopping) {
    if (path_stop_) path_stop_->end();
    return;
  }
  if (last_state_ != DbwState::stopping) {  // the trip
    const bool on_path = path_stop_ && path_stop_->begin(now_s);
    ++(on_path ? counts_.path_stops : counts_.held_stops);
  }
  if (!path_stop_ || !path_stop_->active() || !v) return;
  // The wheel's angle as reported, else the one commanded last.
  const bool heard = fresh_report(RaptorMessage::steering_report, now_ns);
  const double motor_deg = heard ? reports_.steer_motor_deg : setpoint_.actuation.steer_motor_deg;
  const double delta = motor_deg / mapping_.maps().steering_ratio * M_PI / 180;
  const double limit = mapping_.maps().max_steer_rad;
  const StopCommand stop = path_stop_->step(now_s, *v, delta, p_.watchdog.stop_decel_mps2);
  w.command.steer = std::clamp(stop.steer, -limit, limit);
  w.command.brake = brake_for_deceleration(mapping_.maps(), stop.decel);
}

InterfaceStep RaptorInterface::step(int64_t now_ns) {
  InterfaceStep out;
  const double now_s = static_cast<double>(now_ns) * 1e-9;
  for (RaptorMessage m : monitor_.check(now_ns)) {
    char why[120];
    std::snprintf(why, sizeof why, "%s silent: nothing for %g s", raptor_name(m), p_.report_timeout_s);
    out.warnings.push_back(why);
  }
  const std::optional<double> v = speed(now_ns);
  WatchdogOutput w = watchdog_.update(now_s, fresh_, newest_, v);
  fresh_ = false;
  steer_stop(now_s, now_ns, w, v);
  if (w.state != last_state_) {
    out.state_change = state_change(last_state_, watchdog_);
    last_state_ = w.state;
  }
  setpoint_.actuation = to_actuation(w.command, mapping_.maps());
  if (std::string heard = race_.check(now_ns); !heard.empty()) {
    (race_.state().heard ? race_notes_ : out.warnings).push_back(std::move(heard));
    race_read_ = true;
  }
  out.notes = std::move(race_notes_);
  race_notes_.clear();
  out.race_control_changed = std::exchange(race_read_, false);
  setpoint_.track_ack = race_.track_ack(), setpoint_.vehicle_ack = race_.vehicle_ack();
  const bool pt = fresh_report(RaptorMessage::pt_report_1, now_ns);
  setpoint_.gear = shifter_.update(now_s, pt ? reports_.gear : 0, pt ? reports_.engine_rpm : -1, v.value_or(0));
  send_due(now_ns, w.heartbeat, out);
  return out;
}

}  // namespace brickyard::vehicle_interface
