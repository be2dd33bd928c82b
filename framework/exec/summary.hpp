#pragma once
// summary.json (RunSummary::json): the run's result, clock and times, its recording, and every
// node's steps, metrics and port counters.
#include "exec/executive.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <vector>

namespace brickyard::fw {

// s: the run's result, reason and times; recording: close_recording's entry, or null when the
// run kept none.
nlohmann::json summary_json(const RunSummary& s, const GraphDecl& g, const RunOptions& opt, bool sim,
                            const nlohmann::json& recording, const std::vector<std::unique_ptr<NodeRuntime>>& nodes);

}  // namespace brickyard::fw
