// Recording's cost and size on the main job (configs/ims_race.json, two laps of IMS, the whole
// stack on the simulator), every wire but the point clouds, as `--out` records it: ours (MCAP,
// zstd chunks) beside the baseline in the same run (the SQLite .db3 the recorder wrote before,
// still written for FILE.db3) and beside the same run without recording; and ours with the scene
// (/tf, /scene/*: --record-scene on, the default of a recording of every wire), what drawing it adds. Runs alternate so that
// all three see the same load; medians. Exits 1 when a run fails or the two recordings of the
// last round (the sim clock's runs are the same bit for bit) hold other messages per topic.
// usage: bench_recording [--quick] [--runs N]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
// Each topic's message count in a recording, as `brickyard bag info --json` reads it.
std::map<std::string, std::uint64_t> counts(const std::string& by, const std::string& file) {
  std::map<std::string, std::uint64_t> c;
  const std::string info = file + ".info.json";
  if (std::system((by + " bag info " + file + " --json > " + info).c_str()) != 0) return c;
  const auto j = nlohmann::json::parse(std::ifstream(info), nullptr, false);
  if (j.is_object())
    for (const auto& t : j.value("topics", nlohmann::json::array())) c[t.value("name", "")] = t.value("count", std::uint64_t{0});
  return c;
}
}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) runs = 1;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
  }
  const std::string by = BRICKYARD_HOST, graph = std::string(BRICKYARD_SOURCE_DIR) + "/configs/ims_race.json";
  const std::string dir = "/tmp/bench_recording";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // The topics a plain --out run records (everything but the clouds), from one such run.
  std::string topics;
  {
    const std::string cmd = by + " run " + graph + " --quiet --progress 0 --out " + dir + "/out > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) return std::printf("run failed: %s\n", cmd.c_str()), 1;
    const std::string info = dir + "/info.json";
    if (std::system((by + " bag info " + dir + "/out/recording.mcap --json > " + info).c_str()) != 0) return 1;
    const auto j = nlohmann::json::parse(std::ifstream(info));
    for (const auto& t : j["topics"])  // the wires (the scene's channels, foxglove.*, are no wire)
      if (t["type"].get<std::string>().rfind("foxglove.", 0) != 0) topics += (topics.empty() ? "" : ",") + t["name"].get<std::string>();
  }
  std::vector<double> factor[4], mb[4];
  std::map<std::string, std::uint64_t> recorded[4];
  double sim_s = 0;
  for (int i = 0; i < runs; ++i)
    for (int mode : {0, 1, 2, 3}) {  // none, MCAP, SQLite, MCAP with the scene
      const std::string out = dir + "/run", file = dir + (mode == 2 ? "/r.db3" : "/r.mcap");
      fs::remove_all(out);
      fs::remove(file);
      std::string cmd = by + " run " + graph + " --quiet --progress 0 --no-report --out " + out;
      if (mode > 0) cmd += " --record " + file + " --record-only '" + topics + "'";
      if (mode == 3) cmd += " --record-scene on";  // else --record-only leaves it out: the wires alone, as SQLite holds them
      if (std::system((cmd + " > /dev/null 2>&1").c_str()) != 0) return std::printf("run failed: %s\n", cmd.c_str()), 1;
      const auto j = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
      sim_s = j["sim_time_s"].get<double>();
      factor[mode].push_back(sim_s / j["wall_time_s"].get<double>());
      if (mode > 0) mb[mode].push_back(static_cast<double>(fs::file_size(file)) / 1e6);
      if (mode > 0) recorded[mode] = counts(by, file);
    }
  std::printf("recording the main job (configs/ims_race.json, %.1f s of sim time, every wire but the clouds, %d runs each)\n", sim_s, runs);
  std::printf("%-36s %14s %10s %18s\n", "", "x real time", "MB", "cost of recording");
  const double none = median(factor[0]);
  auto row = [&](const char* name, int mode) {
    const double f = median(factor[mode]);
    std::printf("%-36s %14.1f %10.1f %17.1f%%\n", name, f, median(mb[mode]), 100.0 * (none / f - 1.0));
  };
  row("ours: MCAP, zstd chunks", 1);
  row("baseline: SQLite (.db3)", 2);
  row("ours with the scene (the default)", 3);
  std::printf("%-36s %14.1f %10s %18s\n", "not recording", none, "-", "-");
  std::printf("ratio of sizes SQLite / MCAP: %.2f\n", median(mb[2]) / median(mb[1]));
  if (recorded[1].empty() || recorded[1] != recorded[2])
    return std::printf("the recordings disagree: %zu topics in the MCAP, %zu in the SQLite file, or other counts\n",
                       recorded[1].size(), recorded[2].size()), 1;
  return 0;
}
