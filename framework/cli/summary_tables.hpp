#pragma once
// What a run prints on stderr when it ends, from its summary.json.
#include <nlohmann/json.hpp>

#include <string>

namespace brickyard::fw::cli {

// The end of a run at a glance: one row per node with its metrics (arrays cut at four values).
std::string summary_table(const nlohmann::json& j);
// --profile: where the run's wall time went, node by node, most first.
std::string profile_table(const nlohmann::json& j);

}  // namespace brickyard::fw::cli
