#pragma once
// What a GNSS receiver's log holds, by the drivers' decoders: NovAtel OEM7 first and, when that
// decodes nothing, NMEA 0183; its messages by type, the refusals by reason, and the span of the
// times the logs carry. For capture play, each message's bytes and time (the pace of the log).
#include "drivers/common/decode_counters.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace brickyard::fw::cli {

enum class GnssLogProtocol { novatel_oem7, nmea0183 };
const char* to_string(GnssLogProtocol p);  // the drivers.gnss protocol parameter's names

// One message's bytes: from the previous chunk's end to `end` (what came before it, garbage
// included, goes with it). `time_ns` as GnssLogInfo's times; none when the message has no time.
struct GnssChunk {
  std::size_t end = 0;
  std::optional<std::int64_t> time_ns;
  bool message = true;  // false: the bytes after the last message
};

struct GnssLogInfo {
  GnssLogProtocol protocol = GnssLogProtocol::novatel_oem7;
  drivers::DecodeCounters counters;
  std::map<std::string, std::uint64_t> messages;  // by type: "BESTPOSA" (ASCII), "BESTPOSB" (binary), "GPGGA"
  std::uint64_t timed = 0;                        // messages that carry a time
  // OEM7: GPS time, ns since 1980-01-06 (the header's week and milliseconds, where the receiver
  // knew it); NMEA: UTC time of day, ns (GGA, RMC), a day added each time it goes back past midnight.
  std::optional<std::int64_t> first_ns, last_ns;
  std::vector<GnssChunk> chunks;  // with_chunks: every message in order, then any bytes after the last
};

// Decodes `bytes` with the protocol that reads it (above).
GnssLogInfo decode_gnss_log(std::span<const std::uint8_t> bytes, bool with_chunks);

}  // namespace brickyard::fw::cli
