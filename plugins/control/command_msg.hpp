#pragma once
// Command -> ControlCommand, shared by the control plugins.
#include <brickyard/msgs/ControlCommand.h>

#include "motion/command.hpp"

#include <string>

namespace brickyard::control {

inline msgs::ControlCommand command_message(const motion::Command& c, const std::string& source, std::int64_t stamp_ns, std::uint32_t seq) {
  msgs::ControlCommand m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.steer(c.steer);
  m.throttle(c.throttle);
  m.brake(c.brake);
  m.target_speed(c.target_speed);
  m.source(source);
  return m;
}

}  // namespace brickyard::control
