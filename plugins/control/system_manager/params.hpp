#pragma once
// control.system_manager's parameters (plugin.cpp): its rate and deadline, and the manager's
// (common/system_manager.hpp). Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "control/common/system_manager.hpp"

namespace brickyard::control {

struct Settings {
  double rate_hz = 100;
  double step_deadline_s = 0.5;
  ManagerParams manager;
};

inline ParamBinding<Settings> bindings() {
  using M = ManagerParams;
  ParamBinding<Settings> b;
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1, 1000);
  // The last node before the car: a step of it that takes this long (wall time) fails the run,
  // and one stuck at twice it ends the process, for its supervisor to restart (docs/reliability.md).
  // Its steps take microseconds; the car brakes on its own after 0.25 s without a command.
  b.bind("step_deadline_s", &Settings::step_deadline_s).in_unit("s").range(0, 3600)
      .doc("the node's step deadline, wall time (0: none)");
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
  return b;
}

}  // namespace brickyard::control
