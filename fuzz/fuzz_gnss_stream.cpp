// libFuzzer harness: a GNSS receiver's byte stream (a serial port, a UDP socket, a log file)
// through the NovAtel OEM7 and NMEA 0183 decoders, in chunks whose sizes the input's first byte
// picks: any bytes must end as messages or counted refusals, never a crash or a hang. Each OEM7
// binary log decoded is encoded again, as the simulator writes them. The NMEA bytes also go
// through a driver's stream (GGA fixes in the map frame, their sigmas from GST).
#include "drivers/common/gnss_stream.hpp"
#include "drivers/common/nmea0183.hpp"
#include "drivers/common/novatel_oem7.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 64;
  ++data, --size;
  brickyard::drivers::NovatelOem7Decoder oem7;
  brickyard::drivers::Nmea0183Decoder nmea;
  brickyard::drivers::GnssStreamParams p;
  p.protocol = brickyard::drivers::GnssProtocol::nmea0183;
  p.datum = {51.1, -114.0, 1000.0};
  brickyard::drivers::GnssStream stream(p);
  for (std::size_t at = 0; at < size; at += chunk) {
    const std::size_t n = std::min(chunk, size - at);
    oem7.feed(data + at, n);
    nmea.feed(data + at, n);
    stream.feed(data + at, n);
    while (stream.next()) {
    }
    while (const auto m = oem7.next()) (void)brickyard::drivers::encode_oem7_binary(*m);
    while (nmea.next()) {
    }
  }
  oem7.finish();
  nmea.finish();
  while (oem7.next()) {
  }
  while (nmea.next()) {
  }
  return 0;
}
