#pragma once
// vehicle_interface.raptor_dbw's messages of what crosses the bus: the wheel speeds of
// wheel_speed_report, and the frames themselves, raw and decoded (CanFrames). Plugin-side (SDK).
#include <brickyard/msgs/CanFrames.h>
#include <brickyard/msgs/WheelSpeeds.h>

#include "vehicle_interface/common/bus_log.hpp"
#include "vehicle_interface/common/vehicle_can_mapping.hpp"

#include <string>

namespace brickyard::vehicle_interface {

inline msgs::WheelSpeeds speeds_message(const DbwReports& r, std::int64_t now_ns, std::uint32_t seq) {
  msgs::WheelSpeeds m;
  m.header().stamp_ns(now_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.front_left(r.wheel_fl), m.front_right(r.wheel_fr), m.rear_left(r.wheel_rl), m.rear_right(r.wheel_rr);
  return m;
}

inline msgs::CanFrames can_frames_message(const BusLog& log, const std::string& bus, std::int64_t now_ns, std::uint32_t seq) {
  msgs::CanFrames m;
  m.header().stamp_ns(now_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.bus(bus);
  m.frames().reserve(log.frames().size());
  for (const LoggedFrame& l : log.frames()) {
    msgs::CanFrameRecord& r = m.frames().emplace_back();
    r.stamp_ns(l.stamp_ns), r.sent(l.sent), r.id(l.frame.id);
    r.extended(l.frame.extended), r.remote(l.frame.remote), r.fd(l.frame.fd), r.fd_flags(l.frame.fd_flags);
    if (!l.frame.remote) r.data().assign(l.frame.data.begin(), l.frame.data.begin() + l.frame.length);
    if (l.message) r.message(l.message->name);
    r.signals().reserve(l.signals.size());
    for (const auto& [name, value] : l.signals) {
      msgs::CanSignalValue& s = r.signals().emplace_back();
      s.name(name), s.value(value);
    }
  }
  return m;
}

}  // namespace brickyard::vehicle_interface
