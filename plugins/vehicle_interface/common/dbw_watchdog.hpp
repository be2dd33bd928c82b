#pragma once
// The vehicle interface's command watchdog: what goes to the drive-by-wire when the stack's
// commands stop coming. docs/vehicle-interface.md, "When commands stop".
//
//   WAITING      no command yet: throttle off, the stop brake held, heartbeat on. A car that waits
//                longer than first_timeout_s goes on to STOPPING.
//   ACTIVE       the newest command is younger than timeout_s: it is driven.
//   STOPPING     the commands went stale: throttle off, steering held at the last command, the brake
//                that decelerates the car at stop_decel_mps2 by its brakes alone; a fresh command
//                returns to ACTIVE (counted as a recovery).
//   HANDED_OVER  the car has stood (speed under stopped_speed_mps) for hold_s, or the stop has
//                lasted its bound (the speed at the trip, or v_max when no speed was known, over
//                stop_decel_mps2, plus hold_s): the heartbeat (ct_report) stops, so that the
//                drive-by-wire's own safety takes the car. The brake is still commanded. Latched:
//                commands coming back do not restart the heartbeat.
//
// Framework-free; times in seconds of the run's clock.
#include "motion/command.hpp"

#include <optional>
#include <string>

namespace brickyard::vehicle_interface {

struct DbwWatchdogParams {
  double timeout_s = 0.1;          // ten periods of a 100 Hz stack
  double first_timeout_s = 2.0;    // from the interface's first step to the first command
  double stop_decel_mps2 = 6.0;    // the controlled stop
  double stopped_speed_mps = 0.5;  // standing
  double hold_s = 1.0;             // standing this long: heartbeat off
  double v_max_mps = 90;           // the car's top speed: bounds the stop when the speed is not known
};

enum class DbwState { waiting, active, stopping, handed_over };
const char* dbw_state_name(DbwState s);

struct WatchdogOutput {
  motion::Command command;  // what to drive
  bool heartbeat = true;    // whether ct_report goes out
  DbwState state = DbwState::waiting;
};

class DbwWatchdog {
 public:
  // `stop_brake` is the brake pedal (0..1) of the stop: brake_for_deceleration(stop_decel_mps2).
  DbwWatchdog(DbwWatchdogParams p, double stop_brake) : p_(p), stop_brake_(stop_brake) {}

  // Every step: the time, whether a new (and drivable) command came since the last step, the newest
  // command, and the car's speed when a report gives it.
  WatchdogOutput update(double now_s, bool fresh, const motion::Command& newest, std::optional<double> speed_mps);

  DbwState state() const { return state_; }
  int trips() const { return trips_; }            // times commands went stale (or never came)
  int recoveries() const { return recoveries_; }  // times they came back before the handover
  // The longest time without a command up to `now_s`, one still open counted (the stack gone for good).
  double longest_gap_s(double now_s) const { return any_ ? std::max(longest_gap_, now_s - heard_s_) : longest_gap_; }
  double last_command_s() const { return any_ ? heard_s_ : -1; }  // -1: none came
  // The distance and the time the last stop took, from the trip to the standstill (or the handover).
  double stop_distance_m() const { return stop_distance_; }
  double stop_time_s() const { return stop_end_s_ - trip_s_; }
  double stop_bound_s() const { return bound_s_; }

 private:
  void trip(double now_s, std::optional<double> speed_mps);
  bool stop_done(double now_s, std::optional<double> speed_mps);

  DbwWatchdogParams p_;
  double stop_brake_;
  DbwState state_ = DbwState::waiting;
  double start_s_ = -1, heard_s_ = 0, longest_gap_ = 0;
  bool any_ = false;
  double trip_s_ = 0, bound_s_ = 0, stood_since_s_ = -1, stop_end_s_ = 0, last_s_ = 0, stop_distance_ = 0;
  motion::Command last_;
  int trips_ = 0, recoveries_ = 0;
};

}  // namespace brickyard::vehicle_interface
