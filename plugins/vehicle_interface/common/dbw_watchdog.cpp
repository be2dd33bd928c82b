#include "dbw_watchdog.hpp"

#include <algorithm>

namespace brickyard::vehicle_interface {

const char* dbw_state_name(DbwState s) {
  switch (s) {
    case DbwState::waiting: return "WAITING";
    case DbwState::active: return "ACTIVE";
    case DbwState::stopping: return "STOPPING";
    case DbwState::handed_over: return "HANDED_OVER";
  }
  return "?";
}

void DbwWatchdog::trip(double now_s, std::optional<double> speed_mps) {
  ++trips_;
  state_ = DbwState::stopping;
  trip_s_ = stop_end_s_ = last_s_ = now_s;
  stood_since_s_ = -1;
  stop_distance_ = 0;
  bound_s_ = speed_mps.value_or(p_.v_max_mps) / p_.stop_decel_mps2 + p_.hold_s;
}

// Whether the stop is over: the car has stood for hold_s, or the stop has lasted its bound.
bool DbwWatchdog::stop_done(double now_s, std::optional<double> speed_mps) {
  if (speed_mps) stop_distance_ += std::max(*speed_mps, 0.0) * (now_s - last_s_);
  last_s_ = now_s;
  const bool standing = speed_mps && *speed_mps < p_.stopped_speed_mps;
  if (!standing) stood_since_s_ = -1;
  else if (stood_since_s_ < 0) stood_since_s_ = stop_end_s_ = now_s;
  if (!standing) stop_end_s_ = now_s;
  return (standing && now_s - stood_since_s_ >= p_.hold_s) || now_s - trip_s_ >= bound_s_;
}

WatchdogOutput DbwWatchdog::update(double now_s, bool fresh, const motion::Command& newest, std::optional<double> speed_mps) {
  if (start_s_ < 0) start_s_ = now_s;
  if (fresh) {
    if (any_) longest_gap_ = std::max(longest_gap_, now_s - heard_s_);
    heard_s_ = now_s, any_ = true, last_ = newest;
  }
  const bool stale = any_ ? now_s - heard_s_ > p_.timeout_s : now_s - start_s_ > p_.first_timeout_s;
  if (state_ == DbwState::waiting && any_ && !stale) state_ = DbwState::active;
  if ((state_ == DbwState::active || state_ == DbwState::waiting) && stale) trip(now_s, speed_mps);
  if (state_ == DbwState::stopping && !stale) ++recoveries_, state_ = DbwState::active;
  if (state_ == DbwState::stopping && stop_done(now_s, speed_mps)) state_ = DbwState::handed_over;

  WatchdogOutput out;
  out.state = state_;
  out.heartbeat = state_ != DbwState::handed_over;
  if (state_ == DbwState::active) {
    out.command = last_;
    return out;
  }
  out.command.steer = last_.steer;  // held (0 before any command)
  out.command.throttle = 0;
  out.command.brake = stop_brake_;
  return out;
}

}  // namespace brickyard::vehicle_interface
