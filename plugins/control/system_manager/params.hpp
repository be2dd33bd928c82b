#pragma once
// control.system_manager's parameters (plugin.cpp): its rate and deadline, and the manager's
// (common/system_manager.hpp). Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "control/common/flag_gate.hpp"
#include "control/common/system_manager.hpp"
#include "vehicle_param.hpp"

#include <algorithm>
#include <string>

namespace brickyard::control {

struct Settings {
  double rate_hz = 100;
  double step_deadline_s = 0.5;
  ManagerParams manager;
  std::string vehicle = plugins::default_vehicle_file;  // the stop's brake: mass and brake force
  FlagParams flags;
};

// The brake pedal that decelerates the car at `decel` by its brakes alone (the vehicle file's mass
// and brake force; the simulator's brake force is linear in the pedal, docs/vehicle-interface.md).
inline double stop_brake(const vehicle::Vehicle& car, double decel) { return std::clamp(decel * car.mass / car.max_brake_force, 0.0, 1.0); }

// Race control (docs/race-control.md): what the manager does with the flags.
inline void bind_flags(ParamBinding<Settings>& b) {
  using F = FlagParams;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: the stop's brake from its mass and brake force");
  b.bind("stop_decel_mps2", &Settings::flags, &F::stop_decel_mps2).in_unit("m/s^2").range(0.5, 20)
      .doc("race control's stops (red, a lost heartbeat, the checkered lap's end): the deceleration, by the brakes alone; a slow-down to a yellow's target brakes at most this hard");
  b.bind("race_control_timeout_s", &Settings::flags, &F::timeout_s).in_unit("s").range(0.01, 60)
      .doc("no RaceControl message this long: race control lost, a controlled stop");
  b.bind("cap_speed_gain", &Settings::flags, &F::speed_gain).range(0.01, 10)
      .doc("a yellow's cap: pedal per m/s of speed error (brake over the target, at most the throttle under it)");
  b.bind("speed_timeout_s", &Settings::flags, &F::speed_timeout_s).in_unit("s").range(0.01, 10)
      .doc("a yellow's cap needs the car's speed (the estimate input): one older than this is none, and the car stops");
}

inline ParamBinding<Settings> bindings() {
  using M = ManagerParams;
  ParamBinding<Settings> b;
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1, 1000);
  // The last node before the car: a step of it that takes this long (wall time) fails the run,
  // and one stuck at twice it ends the process, for its supervisor to restart (docs/reliability.md).
  // Its steps take microseconds; the car brakes on its own after 0.25 s without a command.
  b.bind("step_deadline_s", &Settings::step_deadline_s).in_unit("s").range(0, 3600)
      .doc("the node's step deadline, wall time (0: derived from its trigger, docs/reliability.md)");
  b.bind("recover_after_s", &Settings::manager, &M::recover_after_s).in_unit("s").range(0, 3600)
      .doc("NORMAL this long before the path tracker drives again");
  b.bind_choice("resume_at", {{"NORMAL", LocStatus::normal}, {"WARNING", LocStatus::warning}}, &Settings::manager, &M::resume_at)
      .doc("the localization status held recover_after_s that hands the path tracker the car back: NORMAL (the paper), or "
           "WARNING (an estimator corrected by one receiver or the prior map again, docs/map-localization.md)");
  b.bind_choice("stop_steering", {{"wall_or_straight", false}, {"wall_or_path", true}}, &Settings::manager, &M::stop_on_path)
      .doc("SAFE_STOP's wheel: the wall follower's while a wall is seen, else straight, or else the path tracker's (on dead "
           "reckoning) while its commands are fresh");
  b.bind("wall_timeout_s", &Settings::manager, &M::wall_timeout_s).in_unit("s").range(0, 3600).doc("no valid wall this long: safe stop");
  b.bind("resume_on_wall", &Settings::manager, &M::resume_on_wall)
      .doc("a car stopped for want of a wall follows it again once it has been valid wall_resume_s (false: it stands until localization is back)");
  b.bind("wall_resume_s", &Settings::manager, &M::wall_resume_s).in_unit("s").range(0, 3600)
      .doc("resume_on_wall: a valid wall this long, frame after frame");
  b.bind("status_timeout_s", &Settings::manager, &M::status_timeout_s).in_unit("s").range(0, 3600)
      .doc("no localization status this long counts as EMERGENCY");
  b.bind_choice("wall_pedals", {{"wall_follower", false}, {"cautious", true}}, &Settings::manager, &M::cautious_pedals)
      .doc("while the wall follower steers: its pedals (the paper), or cautious: the pedals of whichever of it and the path tracker (on dead reckoning) aims lower");
  b.bind("command_timeout_s", &Settings::manager, &M::command_timeout_s).in_unit("s").range(0, 3600)
      .doc("wall_pedals cautious, stop_steering wall_or_path: a path command older than this is not used");
  b.bind("controller_timeout_s", &Settings::manager, &M::controller_timeout_s).in_unit("s").range(0.01, 3600)
      .doc("a controller whose commands have come and then not for this long is silent: not forwarded (to the wall follower, or SAFE_STOP)");
  b.bind("vehicle_timeout_s", &Settings::manager, &M::vehicle_timeout_s).in_unit("s").range(0.01, 3600)
      .doc("input vehicle wired: no vehicle status this long (from the start too) is a silent car side: SAFE_STOP");
  bind_flags(b);
  return b;
}

}  // namespace brickyard::control
