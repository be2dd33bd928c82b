#pragma once
// One run of configs/race.json for the sweeps (eval_tracks, eval_pylons): the host
// started with graph arguments and --set values, its summary read back.
#include "track/centre_line.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace brickyard::bench {

struct RaceRun {
  bool ok = false;  // the run's result is success
  std::string reason;
  nlohmann::json referee, manager, planner;  // their metrics
  nlohmann::json nodes;                      // every node's metrics, by node name
  double sim_s = 0, wall_s = 0;
};

// A metric, NaN when absent or not a number.
double metric(const nlohmann::json& metrics, const char* name);

// `host` run GRAPH --seed --domain --out DIR with each --arg and --set; the log beside DIR.
// Each run in flight needs a DDS domain of its own, so parallel runs never hear each other.
RaceRun run_race(const std::string& host, const std::string& graph, const std::vector<std::string>& args,
                 const std::vector<std::string>& sets, int seed, const std::string& dir, int domain);

// The track files (*.csv) of a folder, sorted by path, each loaded, or with why it could not be.
struct TrackFile {
  std::string path, name;  // absolute path; the file's stem
  track::CenterLine line;
  std::string error;       // not empty: the file could not be loaded
};
std::vector<TrackFile> track_files(const std::string& dir);

// The race graph's arguments for a track file: the track, its outer wall's side (the outside of
// the loop: right on an anticlockwise track), an inner wall too when `both_walls`. IMS is banked
// as the simulator has it by default (9.2°); every other track is flat, said so (a graph of its
// own may default otherwise: configs/map_ims.json banks every curve).
std::vector<std::string> track_args(const std::string& file, const std::string& name, const track::CenterLine& c,
                                    bool both_walls);

// An eval's options come in pairs (--name value). -1: go on; else the exit code: 0 after --help
// (the usage printed), 2 for a name left without its value (a lone --help once started a sweep).
int check_option_pairs(int argc, char** argv, const char* usage);

}  // namespace brickyard::bench
