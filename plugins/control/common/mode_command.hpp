#pragma once
// What the system manager's node sends the car in each mode (system_manager.hpp), framework-free:
// the controller whose last command it forwards and what of that command it replaces, and the
// names the mode goes by in its messages.
#include "motion/command.hpp"
#include "system_manager.hpp"

#include <optional>

namespace brickyard::control {

// A controller's last command: its stamp (s) and what it asked for.
struct ControllerCommand {
  double stamp = 0;
  motion::Command command;
};

enum class Forwarded { none, path, wall };

struct ModeCommand {
  Forwarded forward = Forwarded::none;  // whose last command the car's is a copy of; none: a blank one
  motion::Command command;              // what the car gets
};

// PATH: the path tracker's command (none yet: full brake). WALL: the wall follower's (none yet:
// full brake), with cautious pedals the path tracker's when they slow the car more. SAFE_STOP: full
// brake, no throttle, steering along the wall while the wall follower's command is at most
// wall_timeout_s old (a straight wheel after).
ModeCommand command_for(Mode mode, double t, const std::optional<ControllerCommand>& path, const std::optional<ControllerCommand>& wall,
                        const ManagerParams& p);

// Who drives in a mode: the command's source and ModeStatus.active_controller.
const char* controller_name(Mode m);
// ModeStatus.mode: 0 PATH, 2 WALL_FOLLOW, 3 SAFE_STOP.
int mode_number(Mode m);

}  // namespace brickyard::control
