#pragma once
// Plugin-side (SDK): a driver's `source` parameter read, or refused naming it (exit 2).
#include <brickyard/context.hpp>

#include "drivers/io/byte_source.hpp"

#include <string>

namespace brickyard::drivers {

inline constexpr char kSourceDoc[] =
    "the device: udp://HOST:PORT[?group=G], tcp://HOST:PORT, serial:///dev/X?baud=N&framing=8N1, or a recording: "
    "file://PATH[?rate=R] (GNSS logs), pcap://PATH[?rate=R&port=P] (packets); docs/drivers-transports.md";

inline SourceSpec parse_source_param(const std::string& text) {
  ParsedSource parsed = parse_source(text);
  if (!parsed.spec) throw BadInput("parameter 'source': " + parsed.error);
  return *parsed.spec;
}

}  // namespace brickyard::drivers
