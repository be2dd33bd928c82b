#pragma once
// The system manager obeys race control (docs/race-control.md), framework-free: from race
// control's flags (the RaceControl message the vehicle interface decodes) a state, and what that
// state makes of the command the manager's mode chose (system_manager.hpp, mode_command.hpp).
//   WAITING ── race control heard, GREEN ──► RACING; YELLOW or ORANGE ──► CAUTION
//   RACING ── YELLOW or ORANGE ──► CAUTION: the speed capped at race control's target speed
//   CAUTION ── GREEN ──► RACING
//   RACING, CAUTION ── vehicle flag CHECKERED ──► FINISHING: the lap race control counts is noted
//   FINISHING ── race control's lap count moves on (the lap is finished) ──► FINISHED: a
//                controlled stop, latched (the race is over)
//   WAITING, RACING, CAUTION, FINISHING ── RED, BLACK, PURPLE, a track flag that is not GREEN,
//                YELLOW or ORANGE, a vehicle flag it does not know, or race control lost ──► STOPPING
//   STOPPING ── race control heard again, no flag that stops ──► RACING, CAUTION or FINISHING
// Race control is lost when the interface says its heartbeat has not changed for its
// race_control_timeout_s (RaceControl.heard false), or when no RaceControl message has come for
// timeout_s. WAITING holds the car: the stack never drives before race control is heard.
// The stop, in WAITING, STOPPING and FINISHED: throttle off, the brake that decelerates the car at
// stop_decel_mps2 by the brakes alone (stop_brake, from the vehicle file), the wheel the mode's
// controller steers: along the path. The cap, in CAUTION and in FINISHING under a yellow: over the
// target speed, throttle off and the brake speed_gain x (v - target) (at most the stop's); under
// it, at most the throttle speed_gain x (target - v): the pedals that slow the car more of these
// and the controller's. A cap needs the car's speed (the estimate's, at most speed_timeout_s old);
// without it the car stops.
#include "motion/command.hpp"
#include "motion/race_flags.hpp"

#include <optional>
#include <string>

namespace brickyard::control {

using motion::TrackFlag;
using motion::VehicleFlag;

enum class RaceState { waiting, racing, caution, finishing, stopping, finished };
const char* race_state_name(RaceState s);

struct FlagParams {
  double stop_decel_mps2 = 6.0;  // the controlled stop's deceleration (and the cap's at most)
  double timeout_s = 0.5;        // no RaceControl message this long: race control lost
  double speed_gain = 0.5;       // pedal per m/s of speed error, under the cap
  double speed_timeout_s = 0.2;  // a speed older than this is no speed
};

// One RaceControl message (t: its stamp, s).
struct FlagInput {
  double t = 0;
  bool heard = false;
  TrackFlag track = TrackFlag::none;
  VehicleFlag vehicle = VehicleFlag::none;
  double target_speed = 0;  // m/s
  int lap = 0;
};

struct FlagTransition {
  bool happened = false;
  RaceState from = RaceState::waiting, to = RaceState::waiting;
  std::string reason;
};

// The log line of a transition at time t (s): "race control: RACING -> CAUTION at t = 8.012 s: ...".
std::string flag_line(const FlagTransition& tr, double t);

class FlagGate {
 public:
  // `stop_brake`: the brake pedal (0..1) that decelerates the car at p.stop_decel_mps2.
  FlagGate(FlagParams p, double stop_brake) : p_(p), stop_brake_(stop_brake) {}
  void flags(const FlagInput& f);
  void speed(double t, double v);
  // The state at time t, after whatever the inputs so far imply.
  FlagTransition update(double t);
  RaceState state() const { return state_; }
  // The command the car gets in this state, from the one the mode chose, at time t.
  motion::Command apply(motion::Command c, double t) const;
  // CAUTION, or FINISHING under a yellow: the target speed race control gives.
  bool capped() const;
  double stop_brake() const { return stop_brake_; }

 private:
  RaceState wanted(double t, std::string& why);
  FlagParams p_;
  double stop_brake_;
  RaceState state_ = RaceState::waiting;
  std::optional<FlagInput> last_;
  std::optional<int> checkered_lap_;  // the lap race control counted when the checkered flag came
  double speed_t_ = -1e300, speed_ = 0;
};

}  // namespace brickyard::control
