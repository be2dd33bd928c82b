// libFuzzer harness: a recording (MCAP) through the reader, every message read, as `bag info`,
// the replay plugins and `map build` read one. Damage must stop the reading with damage() saying
// where, or a ReadError naming the file; never a crash, a hang or a huge allocation.
#include "fuzz_input.hpp"
#include "mcap/mcap_reader.hpp"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = brickyard::fuzz::as_file(data, size, ".mcap");
  try {
    const brickyard::mcap::Reader r(path);
    std::size_t n = 0;
    r.read([&](const brickyard::mcap::MessageView&) { ++n; });
  } catch (const std::exception&) {
  }
  return 0;
}
