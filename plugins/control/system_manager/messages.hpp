#pragma once
// control.system_manager's messages: its ModeStatus, and what it reads of the vehicle interface's
// VehicleStatus (docs/vehicle-interface.md: the interface's states and the stale reports' bits).
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/VehicleStatus.h>

#include "control/common/mode_command.hpp"
#include "control/common/system_manager.hpp"

#include <string>

namespace brickyard::control {

inline msgs::ModeStatus mode_message(Mode mode, const std::string& reason, const std::string& controller, std::int64_t stamp_ns,
                                     std::uint32_t seq) {
  msgs::ModeStatus m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.mode(mode_number(mode));
  m.mode_name(mode_name(mode));
  m.reason(reason);
  m.active_controller(controller);
  return m;
}

inline VehicleHealth vehicle_health(const msgs::VehicleStatus& s) {
  constexpr unsigned kBrakeReport = 1u << 1, kSteeringReport = 1u << 3;  // VehicleStatus.stale_reports
  VehicleHealth h;
  h.stopping = s.interface_state() == 2;
  h.handed_over = s.interface_state() == 3;
  h.brake_silent = (s.stale_reports() & kBrakeReport) != 0;
  h.steering_silent = (s.stale_reports() & kSteeringReport) != 0;
  return h;
}

}  // namespace brickyard::control
