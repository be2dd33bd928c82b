#pragma once
// A DBC message to and from a CAN frame: physical values by signal name packed into the frame's
// payload (signals not given are 0 raw), and a frame unpacked into values. Values beyond what a
// signal carries are clamped and named; values outside a signal's declared [min|max] are named,
// on the way in and on the way out, never passed on silently. docs/can-dbc.md.
#include "can_frame.hpp"
#include "dbc.hpp"

#include <map>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

using SignalValues = std::map<std::string, double, std::less<>>;

struct PackResult {
  CanFrame frame;                         // id, format and length from the message
  std::vector<std::string> clamped;       // signals written at the nearest end of what they carry
  std::vector<std::string> out_of_range;  // signals given a value outside their [min|max]
  std::string error;                      // non-empty: nothing was packed (frame left empty)

  bool ok() const { return error.empty(); }
};

// Refused (error): a name the message does not have, NaN or infinity, a multiplexed signal its
// multiplexer's value does not select, Vector's independent-signal holder, extended multiplexing.
PackResult pack_message(const DbcMessage& message, const SignalValues& values);

struct UnpackResult {
  SignalValues values;                    // every signal present in the frame
  std::vector<std::string> out_of_range;  // signals whose value lies outside their [min|max]
  std::string error;                      // non-empty: nothing was unpacked

  bool ok() const { return error.empty(); }
};

// Refused: a frame of another id or format, a remote frame, a payload shorter than the message,
// and the messages pack_message refuses. Multiplexed signals come out only when selected.
UnpackResult unpack_message(const DbcMessage& message, const CanFrame& frame);

}  // namespace brickyard::vehicle_interface
