// Pylons anywhere: configs/race.json on every track in a folder (data/tracks by
// default) with one pylon, at `--places` evenly spaced places round the lap — on the centre line,
// 2 m left of it and 2 m right, in turn — for 2 laps at the car's limit, so the car meets it
// twice: once seen from afar, once after a lap of the line. A run is clean when the race
// finishes (the referee fails a pylon hit, a pass nearer than 0.5 m, a wall contact, a track
// violation, a car that stops). Prints per track: the clean runs, the least pylon and wall
// clearances, and each failed run with its place and reason. docs/results-tracks.md.
// usage: eval_pylons [--tracks DIR] [--places N] [--seed N] [--layout outer|both] [--jobs N] [--domain N] [--set NODE.PARAM=V]...
// Exit 1 when any run failed.
#include "race_runs.hpp"
#include "track/centre_line.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using brickyard::bench::metric;
using brickyard::bench::RaceRun;

namespace {
double lap_length(const brickyard::track::CenterLine& c) {
  double L = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const std::size_t j = (i + 1) % c.x.size();
    L += std::hypot(c.x[j] - c.x[i], c.y[j] - c.y[i]);
  }
  return L;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string src = BRICKYARD_SOURCE_DIR, host = BRICKYARD_HOST;
  std::string tracks = src + "/data/tracks", layout = "outer";
  int places = 10, seed = 0, jobs = 1, domain0 = 150;
  std::vector<std::string> sets;
  if (const int rc = brickyard::bench::check_option_pairs(argc, argv, "usage: eval_pylons [--tracks DIR] [--places N] [--seed N] [--layout outer|both] [--jobs N] [--domain N] [--set NODE.PARAM=V]..."); rc >= 0) return rc;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--tracks")) tracks = argv[i + 1];
    else if (!std::strcmp(argv[i], "--places")) places = std::clamp(std::atoi(argv[i + 1]), 1, 1000);
    else if (!std::strcmp(argv[i], "--seed")) seed = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--layout")) layout = argv[i + 1];
    else if (!std::strcmp(argv[i], "--jobs")) jobs = std::clamp(std::atoi(argv[i + 1]), 1, 16);
    else if (!std::strcmp(argv[i], "--domain")) domain0 = std::clamp(std::atoi(argv[i + 1]), 0, 200);
    else if (!std::strcmp(argv[i], "--set")) sets.push_back(argv[i + 1]);
    else {
      std::fprintf(stderr, "eval_pylons: %s: unknown option\n", argv[i]);
      return 2;
    }
  }
  if (layout != "outer" && layout != "both") {
    std::fprintf(stderr, "eval_pylons: --layout %s: outer or both\n", layout.c_str());
    return 2;
  }
  const std::string dir = std::getenv("EVAL_PYLONS_DIR") ? std::getenv("EVAL_PYLONS_DIR") : "/tmp/eval_pylons";
  fs::create_directories(dir);
  const std::string graph = src + "/configs/race.json";
  std::printf("| track | walls | pylon runs clean | least pylon clearance | least wall clearance |\n|---|---|---|---|---|\n");
  bool all_ok = true;
  for (const auto& tf : brickyard::bench::track_files(tracks)) {
    const std::string& name = tf.name;
    const brickyard::track::CenterLine& c = tf.line;
    if (!tf.error.empty()) {
      std::printf("| %s | %s |\n", name.c_str(), tf.error.c_str());
      all_ok = false;
      continue;
    }
    const double L = lap_length(c);
    const std::vector<std::string> base = brickyard::bench::track_args(tf.path, name, c, layout == "both");
    std::vector<RaceRun> runs(places);
    std::vector<std::pair<double, double>> at(places);
    std::atomic<int> next{0};
    auto worker = [&](int domain) {
      for (int k; (k = next++) < places;) {
        const double s = (k + 0.5) / places * L, d = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 2.0 : -2.0;
        at[k] = {s, d};
        std::vector<std::string> a = base;
        char b[96];
        std::snprintf(b, sizeof b, "pylons=[{\"s\":%.1f,\"d\":%.1f}]", s, d);
        a.push_back(b);
        runs[k] = brickyard::bench::run_race(host, graph, a, sets, seed, dir + "/" + name + "_" + layout + "_pylon" + std::to_string(k),
                                             domain);
      }
    };
    std::vector<std::thread> pool;
    for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, domain0 + j);
    for (auto& th : pool) th.join();
    int clean = 0;
    double pylon = INFINITY, wall = INFINITY;
    std::string failures;
    for (int k = 0; k < places; ++k) {
      const RaceRun& r = runs[k];
      pylon = std::min(pylon, metric(r.referee, "obstacle_min_clearance_m"));
      wall = std::min(wall, metric(r.referee, "min_wall_clearance_m"));
      if (r.ok) {
        ++clean;
      } else {
        char b[64];
        std::snprintf(b, sizeof b, " s = %.0f, d = %+.0f: ", at[k].first, at[k].second);
        failures += b + r.reason + ";";
      }
    }
    std::printf("| %s | %s | %d of %d | %.2f m | %.2f m |\n", name.c_str(), layout.c_str(), clean, places, pylon, wall);
    if (!failures.empty()) {
      std::printf("|  | failed:%s |\n", failures.c_str());
      all_ok = false;
    }
    std::fflush(stdout);
  }
  return all_ok ? 0 : 1;
}
