#include "engagement.hpp"

namespace brickyard::control {

bool Engagement::mode(const std::string& active_controller) {
  path_mode_ = active_controller == "path_tracker";
  const bool active = active_controller == "wall_follower";
  const bool taken = active && !active_;
  if (taken) ++engaged_;
  active_ = active;
  return taken;
}

bool Engagement::before_command() {
  if (!wired_ && engaged_ == 0) {
    ++engaged_;
    return true;
  }
  return wired_ && !active_;
}

}  // namespace brickyard::control
