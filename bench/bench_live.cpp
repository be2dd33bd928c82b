// The live server's cost (docs/live.md): the main job (configs/ims_race.json, two laps of IMS on
// the sim clock, as fast as it goes) with `--live` and one client subscribed to every wire and
// the scene but the point clouds, and to those and the three LiDARs' clouds (as
// foxglove::PointCloud, what the 3D panel shows) — at most 20 a second of wall time each, the
// server's default (--live-cloud-hz), and every one (--live-cloud-hz 0) — beside the same run
// without the server, measured in the same run of this program; runs alternate, and each cost
// is the median of each round's ratio to its own baseline run. The
// client (tests/clients/live_sink.cjs, Node) counts what arrives and decodes nothing; it shares
// these two cores with the run, so its own work is part of the wall-time figure; the run's own CPU
// time (user + system, of the host process alone) is the server's cost without the client's.
// Exits 1 when a run fails, or in a run with the server the server sent nothing or the client
// received nothing (its cost would be that of a server nobody used).
// usage: bench_live [--quick] [--runs N]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace fs = std::filesystem;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) runs = 1;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
  }
  const std::string src = BRICKYARD_SOURCE_DIR, by = BRICKYARD_HOST, graph = src + "/configs/ims_race.json";
  const std::string sink = "node " + src + "/tests/clients/live_sink.cjs ws://127.0.0.1:8766";
  const std::string dir = "/tmp/bench_live";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::vector<double> factor[4], messages[4], mb[4], cpu[4], own[4], server_s[4], taps_s[4];
  double sim_s = 0;
  for (int i = 0; i < runs; ++i)
    for (int mode : {0, 1, 2, 3}) {  // none; a client on all but the clouds; on everything; on everything, every cloud
      const std::string out = dir + "/run";
      fs::remove_all(out);
      std::string client;
      if (mode > 0) {
        // Every wire and the scene but the clouds; then the three LiDARs' too, as the 3D panel
        // takes them (foxglove::PointCloud).
        client = sink + " --skip brickyard::msgs::PointCloud --skip brickyard::msgs::ClusterList --skip foxglove::PointCloud" +
                 (mode >= 2 ? " --keep /lidar/lidar_front.cloud --keep /lidar/lidar_left.cloud --keep /lidar/lidar_right.cloud" : "") +
                 " > " + dir + "/sink.json 2>&1 &";
        if (std::system(client.c_str()) != 0) return 1;
      }
      std::string cmd = by + " run " + graph + " --quiet --progress 0 --no-report --out " + out + (mode > 0 ? " --live 8766" : "") +
                        (mode == 3 ? " --live-cloud-hz 0" : "");
      rusage r0{}, r1{};
      getrusage(RUSAGE_CHILDREN, &r0);
      if (std::system((cmd + " > /dev/null 2>&1").c_str()) != 0) return std::printf("run failed: %s\n", cmd.c_str()), 1;
      getrusage(RUSAGE_CHILDREN, &r1);
      auto secs = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
      cpu[mode].push_back(secs(r1.ru_utime) - secs(r0.ru_utime) + secs(r1.ru_stime) - secs(r0.ru_stime));
      const auto j = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
      sim_s = j["sim_time_s"].get<double>();
      factor[mode].push_back(sim_s / j["wall_time_s"].get<double>());
      if (mode > 0) {
        std::system("sleep 0.5");  // the client writes its count once the server has closed
        const auto live = j.value("live", nlohmann::json::object());
        messages[mode].push_back(live.value("sent", 0.0));
        // The server's own work, counted in the run: its thread's CPU time and the stepping
        // threads' time in the live view's taps, as a share of the run's CPU time (less noisy
        // than a difference of two runs on a shared machine).
        server_s[mode].push_back(live.value("server_cpu_s", 0.0));
        taps_s[mode].push_back(live.value("taps_s", 0.0));
        own[mode].push_back((server_s[mode].back() + taps_s[mode].back()) / cpu[mode].back());
        std::ifstream f(dir + "/sink.json");
        try {
          mb[mode].push_back(nlohmann::json::parse(f).value("bytes", 0.0) / 1e6);
        } catch (...) {
          mb[mode].push_back(0);
        }
      }
    }
  std::printf("the live server on the main job (configs/ims_race.json, %.1f s of sim time, %d runs each)\n", sim_s, runs);
  std::printf("%-48s %12s %14s %10s %10s %8s %10s %9s %8s %9s\n", "", "x real time", "frames sent", "MB", "wall cost", "CPU s",
              "CPU cost", "server s", "taps s", "own share");
  const double none = median(factor[0]), none_cpu = median(cpu[0]);
  // Each cost is the median of the runs' own ratios to the baseline run beside them (the
  // machine's speed drifts between rounds by more than the figures measured).
  auto paired = [&](const std::vector<double>* v, int mode, bool inverse) {
    std::vector<double> r;
    for (std::size_t i = 0; i < v[mode].size() && i < v[0].size(); ++i)
      r.push_back(inverse ? v[0][i] / v[mode][i] - 1.0 : v[mode][i] / v[0][i] - 1.0);
    return 100.0 * median(r);
  };
  auto row = [&](const char* name, int mode) {
    const double f = median(factor[mode]), c = median(cpu[mode]);
    std::printf("%-48s %12.1f %14.0f %10.1f %9.1f%% %8.1f %9.1f%% %9.2f %8.2f %8.1f%%\n", name, f, median(messages[mode]),
                median(mb[mode]), paired(factor, mode, true), c, paired(cpu, mode, false), median(server_s[mode]), median(taps_s[mode]),
                100.0 * median(own[mode]));
  };
  row("ours: a client on all but the clouds", 1);
  row("ours: the same and the 3 LiDAR clouds", 2);
  row("ours: the same, every cloud (--live-cloud-hz 0)", 3);
  std::printf("%-48s %12.1f %14s %10s %10s %8.1f %10s\n", "baseline: no server", none, "-", "-", "-", none_cpu, "-");
  for (int mode : {1, 2, 3})
    for (std::size_t i = 0; i < mb[mode].size(); ++i)
      if (messages[mode][i] <= 0 || mb[mode][i] <= 0)
        return std::printf("the live view measured nothing: in a run the server sent %.0f frames, the client received %.1f MB\n",
                           messages[mode][i], mb[mode][i]), 1;
  return 0;
}
