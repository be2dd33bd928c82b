#pragma once
// The run's recording (--record FILE, docs/recording.md) at both ends of a run: the file with the
// run's metadata before the first sample, and after the last its entry in summary.json.
#include "exec/run_types.hpp"
#include "graph/graph.hpp"
#include "record/recorder.hpp"

#include <nlohmann/json.hpp>

#include <memory>

namespace brickyard::fw {

// Creates opt.record with the run's metadata; throws std::exception naming the file.
std::unique_ptr<Recorder> open_recording(const RunOptions& opt, const GraphDecl& g, bool sim);

// Commits and closes; summary.json's "recording": the file (absolute), messages and bytes.
// Throws std::exception when the file cannot be completed.
nlohmann::json close_recording(Recorder& r);

}  // namespace brickyard::fw
