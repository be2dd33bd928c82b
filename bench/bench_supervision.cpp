// What watching a run costs (target: the supervisor and the watchdogs at most 2 % of
// the main job's wall time), measured in one run of this program:
//  1. the watch around every call into a plugin (crash_guard::Running: which node runs, for the
//     crash handler and the hang watchdog) and a step deadline's two clock reads, per call, beside
//     the same loop without them; times the main job's plugin calls (configs/ims_race.json, from
//     its summary), against its wall time;
//  2. the supervisor of the main job split over two processes (tests/graphs/multiprocess/
//     ims_race_split.json, real clock): its own CPU time beside its processes' (cpu_s in the
//     supervised run's summary).
// usage: bench_supervision [--quick]
#include "exec/crash_guard.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

volatile std::uint64_t g_sink = 0;
void plugin_step() { g_sink = g_sink + 1; }  // a step that does (almost) nothing: all that is left is the watch

// ns per call of n calls, watched (the executive's way) or not.
double per_call_ns(long n, bool watched) {
  const auto t0 = Clock::now();
  for (long i = 0; i < n; ++i) {
    if (watched) {
      const brickyard::fw::crash_guard::Running r("planner", "step", 0.5);
      const auto s0 = Clock::now();
      plugin_step();
      if (Clock::now() - s0 > std::chrono::seconds(1)) g_sink = 0;
    } else {
      plugin_step();
    }
  }
  return std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / static_cast<double>(n);
}
}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && !std::strcmp(argv[1], "--quick");
  const std::string by = BRICKYARD_HOST, src = BRICKYARD_SOURCE_DIR, dir = "/tmp/bench_supervision";
  fs::remove_all(dir);
  fs::create_directories(dir);

  // 1. The watch per call, alternating rounds; medians.
  const long n = quick ? 2'000'000 : 20'000'000;
  std::vector<double> watched, bare;
  for (int r = 0; r < 5; ++r) {
    bare.push_back(per_call_ns(n, false));
    watched.push_back(per_call_ns(n, true));
  }
  const double watch_ns = std::max(median(watched) - median(bare), 0.0);
  // Under a supervisor each call also writes its node and phase into the process's black box.
  std::vector<double> boxed;
  {
    const std::string box = dir + "/black_box";
    setenv("BRICKYARD_BLACKBOX", box.c_str(), 1);
    brickyard::fw::crash_guard::install("");
    for (int r = 0; r < 5; ++r) boxed.push_back(per_call_ns(n, true));
    brickyard::fw::crash_guard::run_ended();
  }
  const double box_ns = std::max(median(boxed) - median(bare), 0.0);
  if (std::system((by + " run " + src + "/configs/ims_race.json --quiet --progress 0 --no-report --out " + dir + "/main > /dev/null 2>&1").c_str()) != 0)
    return std::printf("the main job failed\n"), 1;
  const auto j = nlohmann::json::parse(std::ifstream(dir + "/main/summary.json"));
  double calls = 0;
  for (const auto& [_, node] : j["nodes"].items()) calls += node.value("steps", 0.0);
  const double wall = j["wall_time_s"].get<double>();
  std::printf("1. the watch around each plugin call (node and phase for the crash handler, a step deadline's clock reads)\n");
  std::printf("%-44s %12s\n", "", "ns per call");
  std::printf("%-44s %12.1f\n", "ours: watched", median(watched));
  std::printf("%-44s %12.1f\n", "ours under a supervisor (and its black box)", median(boxed));
  std::printf("%-44s %12.1f\n", "baseline: the same call unwatched", median(bare));
  std::printf("the main job (configs/ims_race.json): %.0f steps in %.2f s of wall time: the watch costs %.3f ms, %.3f%% of it\n", calls, wall,
              calls * watch_ns * 1e-6, 100.0 * calls * watch_ns * 1e-9 / wall);
  std::printf("under a supervisor (black box written around each call): %.3f ms, %.3f%% of it\n", calls * box_ns * 1e-6,
              100.0 * calls * box_ns * 1e-9 / wall);

  // 2. The supervisor of the split main job.
  const std::string cmd = by + " run " + src + "/tests/graphs/multiprocess/ims_race_split.json --quiet --progress 0 --no-report --set referee.laps=0 --duration " +
                          (quick ? "10" : "30") + " --domain 201 --out " + dir + "/split > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) return std::printf("the supervised run failed: %s\n", cmd.c_str()), 1;
  const auto s = nlohmann::json::parse(std::ifstream(dir + "/split/summary.json"));
  const double sup = s["cpu_s"]["supervisor"].get<double>(), procs = s["cpu_s"]["processes"].get<double>(), swall = s["wall_time_s"].get<double>();
  std::printf("2. the supervisor of the main job split over two processes (real clock, %.1f s)\n", swall);
  std::printf("%-44s %12s %14s\n", "", "CPU s", "of wall time");
  std::printf("%-44s %12.3f %13.3f%%\n", "ours: the supervisor", sup, 100.0 * sup / swall);
  std::printf("%-44s %12.3f %13.1f%%\n", "baseline: the processes it watches", procs, 100.0 * procs / swall);
  std::printf("the supervisor's CPU time is %.3f%% of its processes'\n", 100.0 * sup / procs);
  return 0;
}
