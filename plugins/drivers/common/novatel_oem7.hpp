#pragma once
// A streaming decoder of NovAtel OEM7 logs, framework-free: bytes in (any chunking, from a serial
// port, a UDP socket or a file), messages out, no I/O, no global state, no exceptions on bad input.
// It reads ASCII logs ("#BESTPOSA,...*xxxxxxxx", short-header "%RAWIMUSXA,...") and binary logs
// (sync AA 44 12, or AA 44 13 for short headers) of BESTPOS, BESTVEL, INSPVAX and RAWIMUSX, checks
// each log's CRC-32, and counts every refused input by reason (decode_counters.hpp); after garbage
// or a refusal it resynchronises on the next sync. Abbreviated ASCII ("<...") and NMEA sentences in
// the same stream are skipped as bytes between logs. The encoder writes the binary logs with their
// CRC (the simulator's side of the wire). Formats: docs/drivers-formats.md.
#include "decode_counters.hpp"
#include "oem7_messages.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

// How long a log may be before it is refused as oversized. Each bounds the bytes held while a log
// is incomplete, and so how long a false sync in garbage can hold back the logs behind it.
struct Oem7DecoderLimits {
  size_t max_ascii_log_bytes = 32768;    // from the sync character to the CRC's last digit
  size_t max_binary_body_bytes = 16384;  // the binary header's message length field
};

class NovatelOem7Decoder {
 public:
  explicit NovatelOem7Decoder(Oem7DecoderLimits limits = {});

  void feed(const uint8_t* data, size_t size);
  void feed(std::string_view text) { feed(reinterpret_cast<const uint8_t*>(text.data()), text.size()); }
  // The next decoded message, oldest first; nothing when none is waiting.
  std::optional<Oem7Message> next();
  // The stream has ended (file replayed, port closed): a log still incomplete is counted truncated.
  void finish();

  const DecodeCounters& counters() const { return counters_; }

 private:
  void scan();
  std::optional<size_t> try_frame(size_t at);
  std::optional<size_t> try_binary(size_t at);
  std::optional<size_t> try_binary_long(size_t at);
  std::optional<size_t> try_binary_short(size_t at);
  std::optional<size_t> try_ascii(size_t at);
  std::optional<size_t> finish_ascii(size_t at, size_t star);
  size_t skip_garbage(size_t at);
  size_t refuse_binary_crc(size_t at, size_t frame_bytes);
  void accept_binary(uint16_t message_id, const Oem7Header& header, const uint8_t* body, size_t body_bytes);
  void compact();

  Oem7DecoderLimits limits_;
  std::vector<uint8_t> buffer_;
  size_t start_ = 0;  // the first byte not yet consumed
  // Where scanning of the ASCII log at start_ stopped, so a log fed in pieces is scanned once.
  size_t ascii_scanned_ = 0;
  bool ascii_in_quotes_ = false;
  std::deque<Oem7Message> ready_;
  DecodeCounters counters_;
};

// One binary log with its CRC: BESTPOS, BESTVEL and INSPVAX with the long header, RAWIMUSX with the
// short header, as the receiver sends them. The header's message ID and lengths are set here.
std::vector<uint8_t> encode_oem7_binary(const BestPos& m);
std::vector<uint8_t> encode_oem7_binary(const BestVel& m);
std::vector<uint8_t> encode_oem7_binary(const InsPvaX& m);
std::vector<uint8_t> encode_oem7_binary(const RawImuSX& m);
std::vector<uint8_t> encode_oem7_binary(const Oem7Message& m);

}  // namespace brickyard::drivers
