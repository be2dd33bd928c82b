#pragma once
// When control.wall_follower takes over, framework-free. With the system manager's mode wired, the
// follower drives while the manager's active controller is the wall follower, and engages (its
// speed policy starts) at the handover; with no manager, it drives from the first wall frame on.
#include <cstdint>
#include <string>

namespace brickyard::control {

class Engagement {
 public:
  explicit Engagement(bool manager_wired = false) : wired_(manager_wired) {}

  // The manager's active controller: true when the wall follower has just become active (the
  // follower engages now).
  bool mode(const std::string& active_controller);
  // Before a command: whether the follower engages now. With no manager, at the first command;
  // with one, at every command while the follower is not driving: the speed policy starts from
  // now, so the command the manager forwards at the handover holds the car's speed instead of
  // braking for a stale target.
  bool before_command();

  bool active() const { return active_; }
  // Driving, or no manager to say otherwise.
  bool taking_part() const { return active_ || !wired_; }
  // The manager drives the path (localization is good) and the follower stands by: the time to
  // learn where the walls stand from the map's edges.
  bool calibrating() const { return wired_ && !active_ && path_mode_; }
  std::uint64_t engaged() const { return engaged_; }  // take-overs

 private:
  bool wired_ = false;
  bool active_ = false;
  bool path_mode_ = false;
  std::uint64_t engaged_ = 0;
};

}  // namespace brickyard::control
