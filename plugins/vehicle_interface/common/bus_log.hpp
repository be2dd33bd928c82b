#pragma once
// What a vehicle interface wrote to and read off its bus, frame by frame, each decoded by the bus's
// DBC: the record of the bus a recording keeps (vehicle_interface.raptor_dbw publishes it as
// CanFrames, docs/vehicle-interface.md, "Recording the bus"). Framework-free.
#include "can_message.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::vehicle_interface {

struct LoggedFrame {
  int64_t stamp_ns = 0;
  bool sent = false;                   // written by the interface; false: read off the bus
  CanFrame frame;
  const DbcMessage* message = nullptr;  // the DBC's message of its id, if any
  SignalValues signals;                // decoded (empty when the frame does not decode, or decoding is off)
};

class BusLog {
 public:
  // `decode` false: the raw frames only (the message still named).
  BusLog(DbcDatabase db, bool decode) : db_(std::move(db)), decode_(decode) {}

  void add(const std::vector<CanFrame>& frames, int64_t stamp_ns, bool sent);
  // The frames added since the last clear(), in the order added.
  const std::vector<LoggedFrame>& frames() const { return frames_; }
  void clear() { frames_.clear(); }
  // Frames of a DBC message that did not decode (too short, another format), since the start.
  uint64_t undecoded() const { return undecoded_; }

 private:
  DbcDatabase db_;
  bool decode_;
  std::vector<LoggedFrame> frames_;
  uint64_t undecoded_ = 0;
};

}  // namespace brickyard::vehicle_interface
