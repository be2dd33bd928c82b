#pragma once
// Race control's flags as the stack speaks of them (the RaceControl message's track_flag and
// vehicle_flag, sdk/msgs/core/RaceControl.idl): the vehicle interface turns the codes on the bus
// into these (its flag-code parameters, docs/race-control.md), the system manager obeys them.
// The numbers are the message's, fixed: a code on the bus is the interface's business alone.
// Header-only, framework-free.
#include <cstdint>

namespace brickyard::motion {

enum class TrackFlag : std::uint8_t { none = 0, green = 1, yellow = 2, red = 3, orange = 4, unknown = 255 };
enum class VehicleFlag : std::uint8_t { none = 0, checkered = 1, black = 2, purple = 3, unknown = 255 };

inline const char* track_flag_name(TrackFlag f) {
  switch (f) {
    case TrackFlag::none: return "NONE";
    case TrackFlag::green: return "GREEN";
    case TrackFlag::yellow: return "YELLOW";
    case TrackFlag::red: return "RED";
    case TrackFlag::orange: return "ORANGE";
    case TrackFlag::unknown: return "UNKNOWN";
  }
  return "UNKNOWN";
}

inline const char* vehicle_flag_name(VehicleFlag f) {
  switch (f) {
    case VehicleFlag::none: return "NONE";
    case VehicleFlag::checkered: return "CHECKERED";
    case VehicleFlag::black: return "BLACK";
    case VehicleFlag::purple: return "PURPLE";
    case VehicleFlag::unknown: return "UNKNOWN";
  }
  return "UNKNOWN";
}

// A message's number back to the flag: a number the message does not define is unknown.
inline TrackFlag track_flag_of(unsigned v) { return v <= 4 ? static_cast<TrackFlag>(v) : TrackFlag::unknown; }
inline VehicleFlag vehicle_flag_of(unsigned v) { return v <= 3 ? static_cast<VehicleFlag>(v) : VehicleFlag::unknown; }

inline constexpr double kMetresPerSecondPerMph = 0.44704;  // 1609.344 m / 3600 s

}  // namespace brickyard::motion
