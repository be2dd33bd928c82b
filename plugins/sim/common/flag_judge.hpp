#pragma once
// The simulated race control's judge (sim.race_control, docs/race-control.md): did the car do what
// each flag asks, within the distance it needs, from the ground truth? The distance runs along the
// car's path (the truth's positions) from the moment the flag took effect (its first frame):
//  - a yellow or orange with a target speed vt, the car at v0: at vt (within speed_tolerance_mps)
//    within (v0^2 - vt^2) / (2 decel) — the distance the car needs at decel;
//  - a red, a black or purple flag, or a track flag it does not know: stopped (under
//    stopped_speed_mps) within v0^2 / (2 decel) x (1 + stop_margin);
//  - the checkered flag: the lap finished (race control counted it), then stopped within
//    v^2 / (2 decel) x (1 + stop_margin) from the line, v the speed there;
//  - a silence (race control's frames stop): stopped within v0 x silence_allowance_s (the
//    interface's heartbeat timeout and the frames' period: the car may race on that long) plus
//    v0^2 / (2 decel) x (1 + stop_margin).
// Each is said when it is met, and a run fails the moment one is broken or at its end when one was
// never met. A new flag before the last was met leaves it unjudged (said). Framework-free.
#include "race_control_sim.hpp"

#include <optional>
#include <string>
#include <vector>

namespace brickyard::sim {

struct JudgeParams {
  double decel_mps2 = 6.0;           // the deceleration the car stops at (control.system_manager's stop_decel_mps2)
  double stop_margin = 0.10;         // a stop may take this much more than the distance
  double speed_tolerance_mps = 0.5;  // a yellow's target is reached within this
  double stopped_speed_mps = 0.5;
  double silence_allowance_s = 1.1;  // a silence: the time the car may race on before it stops
};

struct JudgeNotice {
  bool fail = false;
  std::string text;
};

class FlagJudge {
 public:
  explicit FlagJudge(JudgeParams p) : p_(p) {}
  // The car's truth at t: position (m) and speed (m/s).
  std::vector<JudgeNotice> truth(double t, double x, double y, double v);
  // An entry of the script took effect at t.
  std::vector<JudgeNotice> flag(double t, const FlagEntry& e);
  // Race control counted a lap at t (laps since the start).
  std::vector<JudgeNotice> lap(double t, int laps);
  // The run ended at t: a goal never met fails it.
  std::vector<JudgeNotice> run_ended(double t);

  double odometer() const { return odo_; }
  int judged() const { return judged_; }  // goals met
  // The last goal met: how far it took and what it was allowed (m).
  double last_distance_m() const { return last_distance_; }
  double last_allowed_m() const { return last_allowed_; }

 private:
  struct Goal {
    std::string what;    // "yellow at 8.000 s from 61.23 m/s"
    double speed = 0;    // reach at most this (+ tolerance), or stop (0)
    bool stop = false;
    double from_odo = 0;
    double needed = 0;   // the braking distance
    double allowed = 0;  // with the margin and allowance
  };
  void start(Goal g);
  JudgeNotice met(const Goal& g);

  JudgeParams p_;
  std::optional<Goal> goal_;
  bool awaiting_lap_ = false;  // checkered: the lap to finish
  std::string checkered_what_;
  std::optional<double> x_, y_;
  double odo_ = 0, v_ = 0;
  int judged_ = 0;
  double last_distance_ = 0, last_allowed_ = 0;
};

}  // namespace brickyard::sim
