#pragma once
// A field of a decoded message named by path, as graphs write it: `header.stamp_ns`, `poses[0].x`,
// `speeds[*]` (every element). Checked against a type's IDL before a run (CdrJson::field_kind),
// then read from each decoded sample. Framework-free.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::cdr {

struct FieldPath {
  static constexpr std::int64_t kEvery = -1;  // [*]
  struct Step {
    std::string member;
    std::vector<std::int64_t> index;  // [N] or [*], in order, after the member
  };
  std::vector<Step> steps;
  std::string text;
};

// Throws std::invalid_argument saying what is wrong with the text ("poses[x]: expected a number or *").
FieldPath parse_field_path(const std::string& text);

// One value a path reaches in a sample, and the concrete path to it ([*] made the index).
struct FieldValue {
  const nlohmann::json* value;
  std::vector<std::int64_t> every;  // the index taken at each [*], in order
};
// Every value at the path, [*] expanded; `missing` gets the first concrete path the sample lacks
// (an index past a sequence's end), empty when none.
void field_values(const nlohmann::json& sample, const FieldPath& path, std::vector<FieldValue>& out, std::string& missing);
// The path with each [*] replaced by the index taken: "poses[4].x".
std::string concrete(const FieldPath& path, const std::vector<std::int64_t>& every);

}  // namespace brickyard::cdr
