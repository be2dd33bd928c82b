// libFuzzer harness: what a graph gives testing.expect and testing.json_source — expectations
// (field paths checked against a type's IDL) and scripted samples (JSON encoded by the IDL) — for
// each message type; what encodes must decode again, by the IDL, to the same JSON's values. The
// first byte picks the type; the rest is JSON text. Bad input must end in std::invalid_argument
// (or the JSON parser's exception), never a crash.
#include "testing/expect/expectations.hpp"
#include "testing/json_source/json_samples.hpp"
#include "message_types.hpp"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& types = fuzzing::message_types();
  if (size == 0) return 0;
  const auto& t = types[data[0] % types.size()];
  const auto j = nlohmann::json::parse(data + 1, data + size, nullptr, false);
  if (j.is_discarded()) return 0;
  try {
    auto e = brickyard::testing::parse_expectations(j, *t.idl, t.name, t.idl.get(), t.name);
    brickyard::testing::ExpectationChecker c(std::move(e));
    c.reference(j);
    c.observe(0, j);
    (void)c.finish();
  } catch (const std::invalid_argument&) {
  } catch (const nlohmann::json::exception&) {
  }
  try {
    for (const auto& s : brickyard::testing::encode_script(j, *t.idl, t.name)) {
      const auto back = t.idl->decode(t.name, s.cdr.data(), s.cdr.size());  // must not throw: it was just written
      (void)back;
    }
  } catch (const std::invalid_argument&) {
  } catch (const nlohmann::json::exception&) {
  }
  return 0;
}
