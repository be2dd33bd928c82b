#pragma once
// summary.json (RunSummary::json): the run's result, clock and times, its recording, and every
// node's steps, metrics and port counters.
#include "exec/run_types.hpp"
#include "graph/graph.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::fw {

class NodeRuntime;

// s: the run's result, reason and times; recording: close_recording's entry, or null when the
// run kept none; end_ns: the run's clock at its end (inputs stale then).
nlohmann::json summary_json(const RunSummary& s, const GraphDecl& g, const RunOptions& opt, bool sim,
                            const nlohmann::json& recording, const std::vector<std::unique_ptr<NodeRuntime>>& nodes,
                            std::int64_t end_ns);

// The inputs stale at now ("node.port 1.2 s" each, comma-separated; empty when none): the progress line.
std::string stale_inputs_text(const std::vector<std::unique_ptr<NodeRuntime>>& nodes, std::int64_t now_ns);

}  // namespace brickyard::fw
