#pragma once
// What a streaming wire decoder did with the bytes it was fed, framework-free. Every refused input
// is counted under exactly one reason, so a node's metrics can say why a sensor's data was dropped
// (docs/drivers-formats.md, "How the decoders refuse bad input").
#include <cstdint>

namespace brickyard::drivers {

struct DecodeCounters {
  uint64_t decoded = 0;          // messages handed out
  uint64_t bad_checksum = 0;     // framed, but its CRC-32 (OEM7) or XOR checksum (NMEA) is wrong
  uint64_t truncated = 0;        // cut short: a line end, the next message or the end of the stream came first
  uint64_t oversized = 0;        // longer than the decoder's limit, or its length field says so
  uint64_t unknown_message = 0;  // checksum good, but a message this decoder does not decode
  uint64_t malformed = 0;        // checksum good, but a field is missing, unreadable or out of range
  uint64_t skipped_bytes = 0;    // bytes between messages that start none (line ends not counted)

  uint64_t refused() const { return bad_checksum + truncated + oversized + unknown_message + malformed; }
};

}  // namespace brickyard::drivers
