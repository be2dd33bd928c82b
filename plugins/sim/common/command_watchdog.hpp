#pragma once
// The car's side of the command contract (docs/simulator.md, "The command watchdog"): a vehicle
// interface that stops hearing from the stack does not hold its last command. Once commands
// have come and then stay away for longer than `timeout_s` (or none has come `first_timeout_s`
// after the car exists), it releases the throttle and brakes at `brake` to a stop, holding the
// last steering angle, until a command comes again. Why: a stack that dies, hangs or loses its
// link mid-lap otherwise leaves the car at full throttle on its last command. Framework-free.
#include "vehicle_model.hpp"

#include <algorithm>

namespace brickyard::sim {

struct CommandWatchdogParams {
  double timeout_s = 0.25;       // the stack's commands come at 50 Hz or more: 12 missed in a row
  double first_timeout_s = 2.0;  // from the car's first step to the first command
  double brake = 0.6;            // the brake pedal while stopping (0..1)
};

class CommandWatchdog {
 public:
  explicit CommandWatchdog(CommandWatchdogParams p = {}) : p_(p) {}

  // Every step: the run's time, whether a new command arrived since the last step, and the
  // newest command (the default when none ever came). Returns the command to apply.
  Command apply(double now, bool fresh, const Command& newest) {
    if (start_ < 0) start_ = now;
    if (fresh) {
      if (any_) longest_gap_ = std::max(longest_gap_, now - heard_);
      heard_ = now, any_ = true;
    }
    const bool stale = any_ ? now - heard_ > p_.timeout_s : now - start_ > p_.first_timeout_s;
    if (stale && !stopping_) ++trips_;
    stopping_ = stale;
    if (!stale) return newest;
    Command c = newest;
    c.throttle = 0;
    c.brake = p_.brake;
    return c;
  }
  bool stopping() const { return stopping_; }
  // Since when it has heard nothing: the last command, or the car's first step before any.
  double quiet_since() const { return any_ ? heard_ : start_; }
  int trips() const { return trips_; }  // times the commands went stale
  // The longest time without a command up to `now`, the one still open counted: how long a stack
  // that died and was restarted was gone, or since when one that died for good has been.
  double longest_gap(double now) const { return any_ ? std::max(longest_gap_, now - heard_) : longest_gap_; }
  double last_command() const { return any_ ? heard_ : -1; }  // when the last one came (-1: none did)

 private:
  CommandWatchdogParams p_;
  double start_ = -1, heard_ = 0, longest_gap_ = 0;
  bool any_ = false, stopping_ = false;
  int trips_ = 0;
};

}  // namespace brickyard::sim
