// libFuzzer harness: bytes off the network or out of a log file, read as a cannelloni UDP
// datagram and as candump log lines (docs/can-dbc.md). Any bytes must end as frames or counted
// refusals, never a crash. What is read must survive a round trip: frames decoded from a
// datagram are encoded and decoded again unchanged, and so are the records of a log.
#include "vehicle_interface/common/candump_log.hpp"
#include "vehicle_interface/common/cannelloni.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

using namespace brickyard::vehicle_interface;

namespace {

void datagram_round_trip(const std::uint8_t* data, std::size_t size) {
  CannelloniDecoder decoder;
  std::vector<CanFrame> frames;
  if (decoder.decode(data, size, frames) != CannelloniRefusal::kNone) {
    if (decoder.counters().refused() != 1 || !frames.empty()) __builtin_trap();
    return;
  }
  std::uint8_t sequence = 0;
  const CannelloniEncoding again = encode_cannelloni(frames, sequence);
  if (!again.error.empty()) __builtin_trap();  // a decoded frame is always one a bus carries
  std::vector<CanFrame> back;
  for (const std::vector<std::uint8_t>& d : again.datagrams)
    if (decoder.decode(d.data(), d.size(), back) != CannelloniRefusal::kNone) __builtin_trap();
  if (back != frames) __builtin_trap();
}

void log_round_trip(const std::uint8_t* data, std::size_t size) {
  const CandumpLog log = read_candump(std::string_view(reinterpret_cast<const char*>(data), size));
  const CandumpLog again = read_candump(write_candump(log.records));
  if (!again.errors.empty() || again.records != log.records) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  datagram_round_trip(data, size);
  log_round_trip(data, size);
  return 0;
}
