// The "race anywhere" sweep: configs/race.json — the full stack, its racing line
// planned for the track at start — on every track in a folder (data/tracks by default), for two
// wall layouts (the outer wall only; a wall at each edge), first without a fault, then with the
// paper's double GNSS fault (both receivers, 7 s) at `--positions` evenly spaced times during lap
// 2 (each fault run goes on for a third lap, so the car's return to the path is seen whatever
// the placement). Prints per track and layout: laps, wall contacts, track violations, least wall clearance
// (over every run), the flying lap against the lap the speed profile plans (the clean run), the
// fault runs that finished clean and came back to the path, the longest time in wall following,
// the runs in which the planner planned around an obstacle (there is none on the track: a wall taken
// for one),
// and the clean run's real-time factor. docs/results-tracks.md.
// usage: eval_tracks [--tracks DIR] [--positions N] [--seed N] [--layout outer|both] [--jobs N] [--domain N] [--set NODE.PARAM=V]...
// --jobs N runs the fault runs N at a time (the clean run, whose real-time factor is reported,
// always runs alone).
// Exit 1 when any run failed (the table says which).
#include "race_runs.hpp"
#include "track/centre_line.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <atomic>
#include <thread>
#include <fstream>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using brickyard::bench::RaceRun;
using Run = RaceRun;

double num(const json& m, const char* k) { return brickyard::bench::metric(m, k); }

std::vector<std::string> g_sets;  // --set, passed to every run

Run run(const std::string& by, const std::string& graph, const std::vector<std::string>& args, int seed, const std::string& dir,
        int domain) {
  return brickyard::bench::run_race(by, graph, args, g_sets, seed, dir, domain);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string src = BRICKYARD_SOURCE_DIR, by = BRICKYARD_HOST;
  std::string tracks = src + "/data/tracks", only_layout;
  int positions = 10, seed = 0, jobs = 1, domain0 = 180;  // domains domain0 .. domain0 + jobs
  if (const int rc = brickyard::bench::check_option_pairs(argc, argv, "usage: eval_tracks [--tracks DIR] [--positions N] [--seed N] [--layout outer|both] [--jobs N] [--domain N] [--set NODE.PARAM=V]..."); rc >= 0) return rc;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--tracks")) tracks = argv[i + 1];
    else if (!std::strcmp(argv[i], "--positions")) positions = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seed")) seed = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--layout")) only_layout = argv[i + 1];
    else if (!std::strcmp(argv[i], "--jobs")) jobs = std::clamp(std::atoi(argv[i + 1]), 1, 16);
    else if (!std::strcmp(argv[i], "--domain")) domain0 = std::clamp(std::atoi(argv[i + 1]), 0, 200);
    else if (!std::strcmp(argv[i], "--set")) g_sets.push_back(argv[i + 1]);
    else {
      std::fprintf(stderr, "eval_tracks: %s: unknown option\n", argv[i]);
      return 2;
    }
  }
  const std::string dir = std::getenv("EVAL_TRACKS_DIR") ? std::getenv("EVAL_TRACKS_DIR") : "/tmp/eval_tracks";
  fs::create_directories(dir);
  const std::string graph = src + "/configs/race.json";
  std::printf("| track | walls | laps | contacts | violations | least clearance | flying lap (× planned) | planned | fault runs clean | back on the path | longest wall following | phantoms | real time |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool all_ok = true;
  for (const auto& tf : brickyard::bench::track_files(tracks)) {
    const std::string& name = tf.name;
    const brickyard::track::CenterLine& c = tf.line;
    if (!tf.error.empty()) {
      std::printf("| %s | %s |\n", name.c_str(), tf.error.c_str());
      all_ok = false;
      continue;
    }
    for (const char* layout : {"outer", "both"}) {
      if (!only_layout.empty() && only_layout != layout) continue;
      const std::vector<std::string> base = brickyard::bench::track_args(tf.path, name, c, std::strcmp(layout, "both") == 0);
      const std::string tag = dir + "/" + name + "_" + layout;
      const Run clean = run(by, graph, base, seed, tag + "_clean", domain0);
      const json& laps = clean.referee.contains("lap_times_s") ? clean.referee["lap_times_s"] : json::array();
      double contacts = num(clean.referee, "wall_contacts"), violations = num(clean.referee, "track_violations");
      double least = num(clean.referee, "min_wall_clearance_m"), longest_wall = 0;
      int clean_faults = 0, back = 0, left = 0, phantoms = 0;
      std::string failures;
      if (!clean.ok) failures += " clean: " + clean.reason + ";";
      // No obstacle stands on these tracks: whatever the planner planned around (seen in enough
      // frames; a single frame's detection is not) was a wall or the ground.
      auto phantom = [&](const Run& r, const std::string& which) {
        if (!(num(r.planner, "obstacles_planned_around_max") > 0)) return;
        ++phantoms;
        failures += " " + which + ": the planner planned around a wall or the ground taken for an obstacle;";
      };
      phantom(clean, "clean");
      if (laps.size() >= 2) {
        const double lap1 = laps[0].get<double>(), lap2 = laps[1].get<double>();
        std::vector<Run> faults(positions);
        std::vector<double> starts(positions);
        std::atomic<int> next{0};
        auto worker = [&](int domain) {
          for (int k; (k = next++) < positions;) {
            const double start = lap1 + (k + 0.5) / positions * lap2;
            std::vector<std::string> a = base;
            char b[64];
            std::snprintf(b, sizeof b, "fault_start=%.3f", start);
            a.push_back(b);
            std::snprintf(b, sizeof b, "fault_end=%.3f", start + 7);
            a.push_back(b);
            // A third lap, so that a fault late in lap 2 is followed to the path's return.
            a.push_back("laps=3");
            starts[k] = start;
            faults[k] = run(by, graph, a, seed, tag + "_fault" + std::to_string(k), domain);
          }
        };
        std::vector<std::thread> pool;
        for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, domain0 + 1 + j);
        for (auto& th : pool) th.join();
        for (int k = 0; k < positions; ++k) {
          const Run& r = faults[k];
          const double start = starts[k];
          contacts += num(r.referee, "wall_contacts");
          violations += num(r.referee, "track_violations");
          least = std::min(least, num(r.referee, "min_wall_clearance_m"));
          if (r.ok && num(r.referee, "wall_contacts") == 0 && num(r.referee, "track_violations") == 0) ++clean_faults;
          else failures += " fault at " + std::to_string(static_cast<int>(start)) + " s: " + r.reason + ";";
          if (num(r.manager, "entered_WALL_FOLLOW") > 0 || num(r.manager, "entered_SAFE_STOP") > 0) {
            ++left;
            if (num(r.manager, "entered_PATH") > 0 && r.manager.value("final_mode", "") == "PATH") ++back;
          }
          longest_wall = std::max(longest_wall, num(r.manager, "time_s_WALL_FOLLOW"));
          phantom(r, "fault at " + std::to_string(static_cast<int>(start)) + " s");
        }
      }
      const double planned = num(clean.planner, "planned_lap_s");
      char flying[64] = "–";
      if (laps.size() >= 2) std::snprintf(flying, sizeof flying, "%.2f s (%.3f×)", laps[1].get<double>(), laps[1].get<double>() / planned);
      std::printf("| %s | %s | %zu | %.0f | %.0f | %.2f m | %s | %.2f s | %d of %d | %d of %d | %.1f s | %d | %.1f× |\n", name.c_str(),
                  layout, laps.size(), contacts, violations, least, flying, planned, clean_faults, positions, back, left, longest_wall, phantoms,
                  clean.wall_s > 0 ? clean.sim_s / clean.wall_s : 0.0);
      if (!failures.empty()) {
        std::printf("|  | failed:%s |\n", failures.c_str());
        all_ok = false;
      }
      std::fflush(stdout);
    }
  }
  return all_ok ? 0 : 1;
}
