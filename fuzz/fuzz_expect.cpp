// libFuzzer harness: what a graph gives testing.expect and testing.json_source — expectations
// (field paths checked against a type's IDL) and scripted samples (JSON encoded by the IDL) — for
// each message type; what encodes must decode again, by the IDL, to the same JSON's values. The
// first byte picks the type; the rest is JSON text. Bad input must end in std::invalid_argument
// (or the JSON parser's exception), never a crash.
#include "cdr/cdr_json.hpp"
#include "expect/expectations.hpp"
#include "json_source/json_samples.hpp"
#include "record/recorder.hpp"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
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
  static const auto idl = [] {
    std::vector<std::unique_ptr<brickyard::cdr::CdrJson>> v;
    for (const auto& t : kIdl) v.push_back(std::make_unique<brickyard::cdr::CdrJson>(brickyard::fw::omgidl_schema(t.text)));
    return v;
  }();
  if (size == 0) return 0;
  const std::size_t k = data[0] % kTypes;
  const auto j = nlohmann::json::parse(data + 1, data + size, nullptr, false);
  if (j.is_discarded()) return 0;
  try {
    auto e = brickyard::testing::parse_expectations(j, *idl[k], kIdl[k].type, idl[k].get(), kIdl[k].type);
    brickyard::testing::ExpectationChecker c(std::move(e));
    c.reference(j);
    c.observe(0, j);
    (void)c.finish();
  } catch (const std::invalid_argument&) {
  } catch (const nlohmann::json::exception&) {
  }
  try {
    for (const auto& s : brickyard::testing::encode_script(j, *idl[k], kIdl[k].type)) {
      const auto back = idl[k]->decode(kIdl[k].type, s.cdr.data(), s.cdr.size());  // must not throw: it was just written
      (void)back;
    }
  } catch (const std::invalid_argument&) {
  } catch (const nlohmann::json::exception&) {
  }
  return 0;
}
