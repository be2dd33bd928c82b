// libFuzzer harness: CDR bytes decoded as each message type by its IDL (libs/cdr/
// cdr_json), as `topic echo` and the recording tools decode samples (the IDL ordered as they order it). The first byte picks the
// type. Bytes that do not fit must end in a runtime_error naming the offset.
#include "message_types.hpp"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& types = fuzzing::message_types();
  if (size == 0) return 0;
  const auto& t = types[data[0] % types.size()];
  try {
    (void)t.idl->decode(t.name, data + 1, size - 1);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
