// libFuzzer harness: a DBC file's text through the reader (docs/can-dbc.md); any text must end
// as a database or as errors with line numbers, never a crash or a hang. A database read is
// then used as the vehicle interface uses it: each message unpacked from a frame made of the
// input's first bytes, the values packed again.
#include "vehicle_interface/common/can_message.hpp"
#include "vehicle_interface/common/dbc.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

using namespace brickyard::vehicle_interface;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const DbcReadResult result = parse_dbc(text, "fuzz.dbc");
  if (!result.ok()) {
    if (result.errors.empty()) __builtin_trap();  // a refused file always says why
    for (const DbcError& e : result.errors) (void)e.text();
    return 0;
  }
  for (const DbcMessage& m : result.database->messages) {
    CanFrame frame;
    frame.id = m.id;
    frame.extended = m.extended;
    frame.length = static_cast<std::uint8_t>(m.length);
    std::copy_n(data, std::min<std::size_t>(size, m.length), frame.data.begin());
    const UnpackResult unpacked = unpack_message(m, frame);
    if (unpacked.ok()) (void)pack_message(m, unpacked.values);
  }
  return 0;
}
