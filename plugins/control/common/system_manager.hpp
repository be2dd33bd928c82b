#pragma once
// The system manager of the paper (§IV), framework-free: which controller's command reaches the
// car, from the localization status and the wall estimate.
//   PATH (path tracker) ── localization EMERGENCY, wall valid ──► WALL (wall follower)
//   PATH ── EMERGENCY, no valid wall ──► SAFE_STOP
//   WALL ── no valid wall for wall_timeout_s ──► SAFE_STOP
//   WALL, SAFE_STOP ── localization NORMAL (or, resume_at WARNING: WARNING or better) held for
//                      recover_after_s ──► PATH
//   SAFE_STOP ── a valid wall held for wall_resume_s, the wall follower alive ──► WALL
//   PATH ── the path tracker's commands stale (controller_timeout_s) ──► WALL, or SAFE_STOP with no valid wall
//   WALL ── the wall follower's commands stale ──► SAFE_STOP
//   PATH, WALL ── the car's side says it is stopping the car, or is silent ──► SAFE_STOP (below)
// A localization status older than status_timeout_s counts as EMERGENCY (a silent estimator is
// not a healthy one); WARNING keeps the path tracker. A controller whose commands have come and
// then stopped (it died or hangs) is not forwarded: its last command would hold the car's last
// throttle; nor is it handed the car back until its commands come again. With the vehicle
// interface watched (watch_vehicle), the car's side counts too: its watchdog stopping the car (the
// commands do not reach it) or having handed it to the drive-by-wire, its steering or brake report
// silent (whether the car steers or brakes is not known), or its status silent for
// vehicle_timeout_s: SAFE_STOP (its wheel the path tracker's while fresh: localization is well),
// held while that lasts and resumed from only once the car's side has been well for
// recover_after_s (a handover never ends). Every transition is returned with its
// reason so the plugin can log and count it. Race control's flags act on the mode's command after
// (flag_gate.hpp: a yellow's cap, a controlled stop).
#include <string>

namespace brickyard::control {

enum class Mode { path, wall, safe_stop };
enum class LocStatus { normal = 0, warning = 1, emergency = 2 };

const char* mode_name(Mode m);

struct ManagerParams {
  double recover_after_s = 2.0;   // NORMAL this long before the path tracker drives again
  // The status at which the path tracker is handed the car back. NORMAL (the paper). WARNING: an
  // estimator whose WARNING means "corrected by some source" (one receiver, or the prior map's
  // poses: estimation's scan_pose_trusted_s) hands the car back once that source corrects it
  // again, though GNSS is still out (docs/map-localization.md).
  LocStatus resume_at = LocStatus::normal;
  // SAFE_STOP's wheel when no wall is seen: false, straight (the paper says nothing); true, the
  // path tracker's while its commands are fresh (it steers on dead reckoning, which holds the
  // racing line for the seconds a stop from speed takes; a straight wheel in a turn meets the wall).
  bool stop_on_path = false;
  // While the wall follower steers: false, its pedals (the paper); true, whichever of its and the
  // path tracker's (on dead reckoning) pedals slow the car more — the paper's wall follower sees
  // 20 m of wall, the path tracker's speed plan the hairpin 200 m ahead.
  bool cautious_pedals = false;
  double command_timeout_s = 0.1; // a path command older than this is not taken for its pedals
  double wall_timeout_s = 0.3;    // no valid wall this long: safe stop
  // A car stopped for want of a wall drives again behind the wall follower once a wall has been
  // valid this long, frame after frame, while localization is still not back (false: it stands
  // until localization is; the paper says nothing). Why: the wall is lost where the road bends
  // out of the detector's reach (an S-bend's exit); stopped, the car often sees it again, and a
  // car standing on a race track for the seconds a fault lasts is a hazard and out of the race.
  bool resume_on_wall = true;
  double wall_resume_s = 1.0;
  double status_timeout_s = 0.5;  // no localization status this long: EMERGENCY
  double controller_timeout_s = 0.25;  // a controller whose commands have come and then not for this long: silent
  double vehicle_timeout_s = 0.5;  // watched: no vehicle status this long (from the start, too): the car's side silent
};

// What the manager reads of the vehicle interface's status.
struct VehicleHealth {
  bool stopping = false;      // its watchdog brakes the car: the stack's commands do not reach it
  bool handed_over = false;   // the drive-by-wire's own safety has the car
  bool steering_silent = false, brake_silent = false;  // their reports
};

struct Transition {
  bool happened = false;
  Mode from = Mode::path, to = Mode::path;
  std::string reason;
};

// Pedals of a command: what cautious_pedals chooses between.
struct Pedals {
  double throttle = 0, brake = 0, target_speed = 0;
};

// The pedals that slow the car more (throttle - brake the lower) of the wall follower's and the
// path tracker's (when its command is fresh), with the lower of their targets.
Pedals cautious(const Pedals& wall, const Pedals& path, bool path_fresh);

class SystemManager {
 public:
  explicit SystemManager(ManagerParams p = {}) : p_(p) {}
  const ManagerParams& params() const { return p_; }
  // The run's start, when not the clock's zero (the real clock's is the epoch's): a status that
  // has not come status_timeout_s after it is a silence.
  void started(double t) { start_t_ = t; }
  // Inputs as they arrive (t in seconds on the run's clock).
  void status(double t, LocStatus s);
  void wall(double t, bool valid);
  void path_command(double t);  // the path tracker sent a command (its stamp)
  void wall_command(double t);  // the wall follower did
  // The vehicle interface's status is watched (a graph that wires it), and a status of it.
  void watch_vehicle() { watch_vehicle_ = true; }
  void vehicle(double t, const VehicleHealth& h);
  // The mode at time t, after whatever the inputs so far imply.
  Transition update(double t);
  Mode mode() const { return mode_; }
  // SAFE_STOP for the car's side alone: localization is well, so the stop may steer along the path.
  bool stopped_for_car() const { return stopped_for_car_; }

 private:
  Transition go(Mode to, std::string reason);
  // What is wrong on the car's side at t ("" when nothing, or when it is not watched).
  std::string vehicle_fault(double t) const;
  ManagerParams p_;
  Mode mode_ = Mode::path;
  LocStatus status_ = LocStatus::normal;
  double status_t_ = -1e300, normal_since_ = -1e300, wall_valid_t_ = -1e300;
  double start_t_ = 0;  // the run's start: no status since then is a silence too
  double wall_valid_since_ = 1e300;  // the start of the reports' current run of valid walls; 1e300: none
  double path_cmd_t_ = -1e300, wall_cmd_t_ = -1e300;  // -1e300: none yet (not silent: not started)
  bool have_status_ = false;
  bool was_resumable_ = false;  // a status good enough to resume at has come this run
  bool watch_vehicle_ = false;
  VehicleHealth vehicle_;
  double vehicle_t_ = -1e300, vehicle_well_since_ = -1e300;  // its last status; since when it counts as well
  double well_run_since_ = 1e300;  // the start of its run of good statuses
  bool handed_over_ = false;  // latched
  bool vehicle_started_ = false;  // well for recover_after_s once
  bool stopped_for_car_ = false;
};

}  // namespace brickyard::control
