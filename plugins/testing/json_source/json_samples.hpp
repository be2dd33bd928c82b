#pragma once
// testing.json_source's script: samples of any message type written as JSON, each with the time
// it is published, encoded by the type's IDL once, before the run (docs/testing.md).
// Framework-free: unit tests call it directly.
#include "cdr/cdr_json.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::testing {

struct ScriptedSample {
  std::int64_t t_ns;                 // when it is published, on the run's clock
  std::vector<unsigned char> cdr;    // the message, encoded
};

// [{"t": 0.5, "msg": {...}}, ...], times non-decreasing. A message whose type has
// header.stamp_ns and that gives none is stamped with its time. Throws std::invalid_argument
// naming the JSON pointer of what is wrong ("/3/msg/poses/0/x: expected a number, found \"a\"").
std::vector<ScriptedSample> encode_script(const nlohmann::json& script, const cdr::CdrJson& idl, const std::string& type);

}  // namespace brickyard::testing
