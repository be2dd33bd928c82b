#pragma once
// A streaming decoder of NMEA 0183 sentences (GGA, RMC, VTG), framework-free: bytes in, messages
// out, no I/O, no global state, no exceptions on bad input. Each sentence's XOR checksum is checked
// (a sentence without one is refused: every receiver we read sends it), refusals are counted by
// reason like novatel_oem7.hpp's, and the decoder resynchronises on the next '$'. The encoders
// write GGA and RMC with their checksum, for the simulator and round-trip tests.
// Formats: docs/drivers-formats.md.
#include "decode_counters.hpp"
#include "nmea0183_messages.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

// NMEA 0183 (3.01, section 5.3) caps a sentence at 82 characters with its "$" and line end, but
// receivers exceed it (NovAtel's GPRMC with 7-decimal minutes is 87); the cap here, from '$' to the
// checksum's last digit, leaves room for them and still refuses runaway input.
struct NmeaDecoderLimits {
  size_t max_sentence_bytes = 120;
};

class Nmea0183Decoder {
 public:
  explicit Nmea0183Decoder(NmeaDecoderLimits limits = {});

  void feed(const uint8_t* data, size_t size);
  void feed(std::string_view text) { feed(reinterpret_cast<const uint8_t*>(text.data()), text.size()); }
  std::optional<NmeaMessage> next();
  // The stream has ended: a sentence still incomplete is counted truncated.
  void finish();

  const DecodeCounters& counters() const { return counters_; }

 private:
  void scan();
  std::optional<size_t> try_sentence(size_t at);
  std::optional<size_t> finish_sentence(size_t at, size_t star);
  size_t skip_garbage(size_t at);
  void compact();

  NmeaDecoderLimits limits_;
  std::vector<uint8_t> buffer_;
  size_t start_ = 0;
  size_t scanned_ = 0;  // where scanning of the sentence at start_ stopped
  std::deque<NmeaMessage> ready_;
  DecodeCounters counters_;
};

// The XOR of every byte of `text` (a sentence between '$' and '*').
uint8_t nmea_checksum(std::string_view text);
// "$" + text + "*HH\r\n": the sentence whole, its checksum computed.
std::string seal_nmea(const std::string& text);

// Whole sentences, "$" to "\r\n", with their checksum. Latitude and longitude are written with
// 7 decimals of minutes (about 0.2 mm), as NovAtel's receivers do.
std::string encode_gga(const NmeaGga& m);
std::string encode_rmc(const NmeaRmc& m);

}  // namespace brickyard::drivers
