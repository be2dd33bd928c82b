#pragma once
// CAN frames over UDP in cannelloni's format (github.com/mguentner/cannelloni, doc/udp_format.md,
// "format version 2"), bytes in and out, no sockets. A datagram is a 5-byte header — version (2),
// op code (0, DATA), sequence number, frame count (16 bits) — then the frames, each the can_id of
// linux/can.h (32 bits, its EFF/RTR/ERR flags included), a length byte (bit 7 set for CAN FD, then
// a flags byte) and the data (none for a remote request). Everything big-endian. docs/can-dbc.md.
//
// Decoding takes a datagram whole or not at all: a datagram whose structure is broken anywhere is
// refused, counted under one reason, and none of its frames comes out.
#include "can_frame.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

inline constexpr uint8_t kCannelloniVersion = 2;
inline constexpr uint8_t kCannelloniOpData = 0;
inline constexpr size_t kCannelloniHeaderBytes = 5;
// An Ethernet MTU of 1500 less the IPv4 (20) and UDP (8) headers: datagrams that are not fragmented.
inline constexpr size_t kCannelloniDefaultMaxDatagram = 1472;

enum class CannelloniRefusal {
  kNone,
  kShortDatagram,   // under the 5-byte header
  kBadVersion,      // version other than 2
  kBadOpCode,       // not DATA (cannelloni's ACK and NACK belong to its SCTP transport)
  kTruncatedFrame,  // the count promises a frame the datagram does not hold whole
  kBadLength,       // over 8 bytes for a classic frame, not a CAN FD length, a remote FD frame
  kBadId,           // an 11-bit frame whose id is over 0x7FF
  kTrailingBytes,   // bytes after the frames the count names
};
const char* refusal_name(CannelloniRefusal refusal);

struct CannelloniCounters {
  uint64_t datagrams = 0;     // offered to decode()
  uint64_t frames = 0;        // handed out
  uint64_t error_frames = 0;  // CAN_ERR_FLAG frames of accepted datagrams: passed over
  uint64_t short_datagram = 0;
  uint64_t bad_version = 0;
  uint64_t bad_op_code = 0;
  uint64_t truncated_frame = 0;
  uint64_t bad_length = 0;
  uint64_t bad_id = 0;
  uint64_t trailing_bytes = 0;

  uint64_t refused() const {
    return short_datagram + bad_version + bad_op_code + truncated_frame + bad_length + bad_id + trailing_bytes;
  }
  void count(CannelloniRefusal refusal);
};

class CannelloniDecoder {
 public:
  // Appends the datagram's frames to `frames` (none when refused) and says why it was refused.
  CannelloniRefusal decode(const uint8_t* datagram, size_t size, std::vector<CanFrame>& frames);
  const CannelloniCounters& counters() const { return counters_; }
  // The sequence number of the last datagram accepted (cannelloni counts them modulo 256).
  uint8_t last_sequence() const { return last_sequence_; }

 private:
  CannelloniCounters counters_;
  uint8_t last_sequence_ = 0;
};

struct CannelloniEncoding {
  std::vector<std::vector<uint8_t>> datagrams;
  std::string error;  // non-empty: a frame cannot be sent (frame_problem), nothing encoded
};

// The frames in order, as few datagrams as fit `max_datagram_bytes` each (at least one frame per
// datagram; none for no frames), numbered from `sequence` on, modulo 256; `sequence` is left
// at the next number.
CannelloniEncoding encode_cannelloni(const std::vector<CanFrame>& frames, uint8_t& sequence,
                                     size_t max_datagram_bytes = kCannelloniDefaultMaxDatagram);

}  // namespace brickyard::vehicle_interface
