#pragma once
// `brickyard run --out DIR`: the folder a run keeps its summary, recording and report in. A run
// replaces what an earlier run wrote there, and nothing else.
#include <string>

namespace brickyard::fw::cli {

// The recording `--out DIR` writes (everything but point clouds), which the report reads.
inline constexpr const char* kOutRecording = "recording.mcap";

// Makes the folder (if need be); refuses (InvalidInput) a summary.json that is not a run's or a
// report.html that is not brickyard-report's: those are the user's.
void prepare_out_folder(const std::string& out);
// The same refusals, making nothing: before the plugins load, so that a crash while loading may
// write its summary there (crash_guard::set_summary_path) without replacing one of the user's.
void refuse_foreign_out_files(const std::string& out);

// Removes what an earlier run left in the folder (its report, summary, and its recording when the
// folder's own), so that nothing stale is drawn; refuses a recording there that --record made,
// or that `record` (the run's --record FILE) is.
void clear_earlier_run(const std::string& out, const std::string& record);

}  // namespace brickyard::fw::cli
