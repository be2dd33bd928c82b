// `brickyard map build RECORDING --out DIR`: configs/map_build.json (built in) on the recording.
// What is wrong with the file is said before anything runs (exit 2); a drive from which no
// track could be made is bad input too (the recording is the input), and leaves no track file.
#include "cli/command_table.hpp"
#include "cli/run_command.hpp"
#include "record/recording_info.hpp"

#include "map_build_graph.hpp"  // generated: part of the brickyard executable only

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace brickyard::fw::cli {
namespace {

namespace fs = std::filesystem;

void check_map_arguments(const Args& a) {
  if (a.target != "build")
    usage_error(a.target.empty() ? "map" : "map " + a.target, a.target.empty() ? "needs a command (brickyard map build RECORDING --out DIR)"
                                                                             : "unknown map command (brickyard map build RECORDING --out DIR)");
  if (a.more.size() != 1) usage_error("map build", "needs one recording (brickyard run GRAPH --record FILE)");
  if (a.out.empty()) usage_error("map build", "needs --out DIR (for DIR/track.csv, DIR/map.pcd, DIR/summary.json)");
}

// The recording, refused unless whole, holding samples, on the sim or real clock.
RecordingInfo read_drive(const std::string& rec) {
  RecordingInfo info;
  try {
    info = read_recording_info(rec);
  } catch (const std::exception& e) {
    usage_error(rec, e.what());
  }
  if (!info.damage.empty()) usage_error(rec, info.damage);
  if (info.messages == 0) usage_error(rec, "the recording holds no samples");
  if (info.clock != "sim" && info.clock != "real")
    usage_error(rec, "recorded on the " + (info.clock.empty() ? std::string("unknown") : info.clock) + " clock: neither sim nor real");
  return info;
}

// A real drive's recording (Unix times) is re-timed onto the sim clock from its first sample.
std::int64_t first_sample_ns(const std::string& rec, const RecordingInfo& info) {
  std::int64_t first_ns = 0;
  if (info.clock == "real") {
    bool any = false;
    for (const auto& t : read_topic_stats(rec))
      if (t.count) first_ns = any ? std::min(first_ns, t.first_ns) : t.first_ns, any = true;
  }
  return first_ns;
}

// The graph's arguments: the user's --arg, then the ones map build sets itself (refused from the user).
std::vector<std::string> map_graph_args(const Args& a, const std::string& rec, const RecordingInfo& info, std::int64_t first_ns,
                                        const fs::path& track, const fs::path& map) {
  std::vector<std::string> args = a.args;
  args.push_back("recording=" + fs::absolute(rec).string());
  args.push_back("map_file=" + map.string());
  args.push_back("track_file=" + track.string());
  char duration[64];
  std::snprintf(duration, sizeof duration, "duration=%.3f", static_cast<double>(info.last_ns - first_ns) * 1e-9 + 0.1);
  args.push_back(duration);
  if (info.clock == "real") args.push_back("retime_from_ns=" + std::to_string(first_ns));
  return args;
}

// Why the mapper made no track (its metric track_error), from DIR/summary.json; empty if it does not say.
std::string why_no_track(const fs::path& dir) {
  std::ifstream f(dir / "summary.json");
  std::string why;
  try {
    why = nlohmann::json::parse(f).at("nodes").at("mapper").at("metrics").value("track_error", "");
  } catch (...) {
  }
  return why;
}

}  // namespace

int cmd_map(const Args& a) {
  check_map_arguments(a);
  const std::string rec = a.more[0];
  const RecordingInfo info = read_drive(rec);
  const std::int64_t first_ns = first_sample_ns(rec, info);
  for (const auto& arg : a.args)
    for (const char* ours : {"recording=", "map_file=", "track_file=", "duration=", "retime_from_ns="})
      if (arg.rfind(ours, 0) == 0) usage_error("--arg " + arg, "map build sets this one itself");
  std::error_code ec;
  fs::create_directories(a.out, ec);
  if (ec) usage_error("--out " + a.out, "cannot create the folder: " + ec.message());
  const fs::path dir = fs::absolute(a.out), track = dir / "track.csv", map = dir / "map.pcd";
  for (const char* own : {"recording.mcap", "recording.db3"})
    if (fs::equivalent(rec, dir / own, ec))
      usage_error("--out " + a.out, std::string("holds the recording as ") + own + ", which a run into the folder replaces: use another folder");
  // An earlier build's files must not stand for this one's.
  fs::remove(track, ec);
  fs::remove(map, ec);
  const std::vector<std::string> args = map_graph_args(a, rec, info, first_ns, track, map);
  Args run = a;
  run.no_report = true;  // DIR gets the summary; the recording is the input, not recorded again
  const int rc = run_graph(run, parse_graph_text(kMapBuildGraph, "configs/map_build.json (built into brickyard)", a.sets, args), false);
  if (rc != 1) {
    if (rc == 0) std::printf("map build: %s and %s from %s\n", track.c_str(), map.c_str(), rec.c_str());
    return rc;
  }
  // The mapper could make no track (no lap in the drive, no edge found; its metric track_error
  // says why): the recording's fault.
  const std::string why = why_no_track(dir);
  if (!why.empty()) {
    std::fprintf(stderr, "error: %s: no track from this drive: %s\n", rec.c_str(), why.c_str());
    return 2;
  }
  return rc;
}

}  // namespace brickyard::fw::cli
