// What DDS security costs (target: at most 10 % of the split race's wall time), measured
// in one run of this program: the main job split over two processes (tests/graphs/multiprocess/
// ims_race_split.json, real clock, supervised) with `transport.security` on — every participant
// authenticated, each wire access-controlled, every RTPS message signed (`brickyard security
// init`, --protect sign) — and every RTPS message encrypted instead (--protect encrypt),
// beside the same run without security, runs alternating. The real clock fixes the wall time, so
// the cost is the processes' CPU time (cpu_s in the supervised run's summary) over it; and the
// car's longest gap between commands (sim.vehicle's longest_command_gap_s), which security must not
// stretch.
// Exits 1 when a run fails or its car went 0.5 s without a command (the wires did not carry).
// usage: bench_security [--quick]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Run {
  double cpu_s = 0, wall_s = 0, gap_s = 0;
};
}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && !std::strcmp(argv[1], "--quick");
  const std::string by = BRICKYARD_HOST, src = BRICKYARD_SOURCE_DIR, dir = "/tmp/bench_security";
  const std::string graph = src + "/tests/graphs/multiprocess/ims_race_split.json";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* p : {"sign", "encrypt"}) {
    const std::string cmd = by + " security init " + graph + " --out " + dir + "/keys_" + p + " --protect " + p + " > /dev/null";
    if (std::system(cmd.c_str()) != 0) return std::printf("security init failed: %s\n", cmd.c_str()), 1;
  }
  const int rounds = quick ? 1 : 3;
  const char* duration = quick ? "10" : "30";
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"ours: security on, traffic signed", dir + "/keys_sign"},
      {"ours: security on, traffic encrypted", dir + "/keys_encrypt"},
      {"baseline: no security", "off"}};
  std::vector<std::vector<Run>> runs(variants.size());
  for (int r = 0; r < rounds; ++r)
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const std::string out = dir + "/run_" + std::to_string(v) + "_" + std::to_string(r);
      const std::string cmd = by + " run " + graph + " --quiet --progress 0 --no-report --set referee.laps=0 --duration " + duration +
                              " --domain 202 --arg security=" + variants[v].second + " --out " + out + " > /dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0) return std::printf("the run failed: %s\n", cmd.c_str()), 1;
      const auto s = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
      Run x;
      x.cpu_s = s["cpu_s"]["processes"].get<double>();
      x.wall_s = s["wall_time_s"].get<double>();
      const auto sim = nlohmann::json::parse(std::ifstream(out + "/sim/summary.json"));
      x.gap_s = sim["nodes"]["car"]["metrics"]["longest_command_gap_s"].get<double>();
      if (!(x.gap_s < 0.5))  // the wires carried nothing (or stalled): a cost of security that did not work
        return std::printf("the car went %.3f s without a command: %s\n", x.gap_s, cmd.c_str()), 1;
      runs[v].push_back(x);
    }
  auto med = [&](std::size_t v, double Run::*f) {
    std::vector<double> xs;
    for (const auto& x : runs[v]) xs.push_back(x.*f);
    return median(xs);
  };
  const std::size_t base = variants.size() - 1;
  std::printf("DDS security on the main job split over two processes (tests/graphs/multiprocess/ims_race_split.json, real clock, %s s, %d run%s each)\n",
              duration, rounds, rounds > 1 ? "s" : "");
  std::printf("%-40s %8s %8s %12s %18s\n", "", "wall s", "CPU s", "cost", "longest cmd gap s");
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const double cost = (med(v, &Run::cpu_s) - med(base, &Run::cpu_s)) / med(v, &Run::wall_s);
    char c[32] = "-";
    if (v != base) std::snprintf(c, sizeof c, "%.1f%%", 100 * cost);
    std::printf("%-40s %8.1f %8.2f %12s %18.3f\n", variants[v].first.c_str(), med(v, &Run::wall_s), med(v, &Run::cpu_s), c, med(v, &Run::gap_s));
  }
  std::printf("cost: the processes' extra CPU time over the run's wall time (the issue's target: at most 10%%)\n");
  return 0;
}
