#include "mode_command.hpp"

namespace brickyard::control {

namespace {

// With cautious pedals, the wall follower's pedals or the path tracker's (when fresh), whichever
// slow the car more.
void take_cautious_pedals(double t, const ControllerCommand& path, const ManagerParams& p, motion::Command& c) {
  const bool fresh = t - path.stamp <= p.command_timeout_s;
  const motion::Command& q = path.command;
  const Pedals pedals = cautious({c.throttle, c.brake, c.target_speed}, {q.throttle, q.brake, q.target_speed}, fresh);
  c.throttle = pedals.throttle;
  c.brake = pedals.brake;
  c.target_speed = pedals.target_speed;
}

}  // namespace

ModeCommand command_for(Mode mode, double t, const std::optional<ControllerCommand>& path, const std::optional<ControllerCommand>& wall,
                        const ManagerParams& p) {
  ModeCommand out;
  motion::Command& c = out.command;
  switch (mode) {
    case Mode::path:
      if (path) {
        out.forward = Forwarded::path;
        c = path->command;
      } else {
        c.brake = 1.0;  // nothing to forward yet
      }
      break;
    case Mode::wall:
      if (wall) {
        out.forward = Forwarded::wall;
        c = wall->command;
        if (p.cautious_pedals && path) take_cautious_pedals(t, *path, p, c);
      } else {
        c.brake = 1.0;
      }
      break;
    case Mode::safe_stop:
      // Full brake; keep following the wall's line while it is seen (a command of the last
      // wall_timeout_s), else the path tracker's wheel when stop_on_path and fresh, else straight.
      if (wall && t - wall->stamp <= p.wall_timeout_s) c.steer = wall->command.steer;
      else if (p.stop_on_path && path && t - path->stamp <= p.command_timeout_s) c.steer = path->command.steer;
      else c.steer = 0.0;
      c.brake = 1.0;
      break;
  }
  c.throttle = mode == Mode::safe_stop ? 0.0 : c.throttle;
  return out;
}

const char* controller_name(Mode m) { return m == Mode::path ? "path_tracker" : m == Mode::wall ? "wall_follower" : "safe_stop"; }

int mode_number(Mode m) { return m == Mode::path ? 0 : m == Mode::wall ? 2 : 3; }

}  // namespace brickyard::control
