// libFuzzer harness: CDR bytes decoded as each message type by its IDL (libs/cdr/
// cdr_json), as `topic echo` and the recording tools decode samples (the IDL ordered as they order it). The first byte picks the
// type. Bytes that do not fit must end in a runtime_error naming the offset.
#include "cdr/cdr_json.hpp"
#include "record/recorder.hpp"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {
struct IdlText {
  const char* type;
  const char* text;
};
const IdlText kIdl[] = {
#include "idl_texts.inc"
};
constexpr std::size_t kTypes = sizeof kIdl / sizeof kIdl[0];
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto decoders = [] {
    std::vector<std::unique_ptr<brickyard::cdr::CdrJson>> v;
    for (const auto& t : kIdl) v.push_back(std::make_unique<brickyard::cdr::CdrJson>(brickyard::fw::omgidl_schema(t.text)));
    return v;
  }();
  if (size == 0) return 0;
  const std::size_t k = data[0] % kTypes;
  try {
    (void)decoders[k]->decode(kIdl[k].type, data + 1, size - 1);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
