// Simulator speed. Each part beside its baseline measured in the same run:
//  1. LiDAR ray casting on IMS (three AV-21 Hydras, 32 x 850 rays each, poses all around the
//     track): ours (slab march with block skipping, rows of a column resuming where the row below
//     left off) vs the plain slab march (every ray walks every slab from the sensor).
//     Prints rays per second and the LiDAR-only real-time factor (one frame = 1/20 s).
//  2. The full simulator graph configs/sim_truth_lap.json (car at 500 Hz, 2 GNSS, IMU, wheels,
//     3 LiDARs, referee, driver) on the sim clock: sim_time_s / wall_time_s against real time (1x),
//     without recording (the simulator) and recording as a plain --out run does (beside it), and
//     stepped on one thread (--threads 1: no node stepped side by side).
//  3. The whole stack, configs/race.json on Spielberg (walls at both edges, no fault): the same
//     factor over the whole run and steady (less the start: planning the line, building the road
//     graph), the executive's default threads against --threads 1 and against the simulator alone
//     (target: 15x).
//  4. With --map FILE (the track's map: scripts/track-map Spielberg both), the stack on its map,
//     configs/race_on_map.json, beside race.json, runs alternating: each factor once started
//     (sim seconds over the wall seconds past those of a 0.1 s run of the same graph: the map read
//     and its voxels built, once a race), and their ratio (issue 41: at least 15x); and the same
//     locating every frame, as through a GNSS outage (normal_interval_s 0).
// Exits 1 when a run fails (other than a race cut short by --duration) or when the casters'
// variants return other numbers of points on the same poses (more than 0.1 % apart).
// usage: bench_sim [--quick] [--map FILE]   (--quick: 40 poses, 3 rounds; 20 s runs, once)
#include "sim/common/lidar.hpp"
#include "sim/common/track.hpp"

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

using namespace brickyard::sim;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Pose {
  Eigen::Isometry3d T;
  int seg;
};

struct RunTimes {
  double sim_s = 0, wall_s = 0;
};

std::vector<Pose> poses_around(const Track& t, int count, double d) {
  std::vector<Pose> out;
  for (int i = 0; i < count; ++i) {
    Frenet f = t.at(t.length() * i / count, d);
    Eigen::Vector2d p = t.position(f), g = t.road_gradient(f);
    double yaw = t.heading(f), c = std::cos(yaw), s = std::sin(yaw);
    double pitch = -std::atan(g.x() * c + g.y() * s), roll = std::atan(-g.x() * s + g.y() * c);
    Eigen::Isometry3d T = Eigen::Translation3d(p.x(), p.y(), t.road_z(f)) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
    out.push_back({T, f.seg});
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string map;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[i], "--map") == 0 && i + 1 < argc) map = argv[++i];
  const std::string src = BRICKYARD_SOURCE_DIR;
  WorldSpec w;
  w.line = load_centerline_csv(src + "/data/tracks/IMS.csv");
  w.name = "IMS";
  BankSpec b;
  b.mode = "curvature";
  b.degrees = 9.2;
  b.curvature_threshold = 0.002;
  w.bank = bank_profile(w.line, b);
  w.walls.right = true;  // the outside of the counter-clockwise loop
  w.walls.height = 1.2;
  Track track(w);
  const auto poses = poses_around(track, quick ? 40 : 200, -2.0);

  std::printf("LiDAR ray casting, IMS, 3 sensors x 32 x 850 rays, %zu poses around the track\n", poses.size());
  std::printf("%-34s %14s %12s %14s\n", "caster", "Mrays/s", "ms/frame", "LiDAR x RT");
  double ours_rate = 0, base_rate = 0, one_thread_rate = 0;
  std::size_t hits[3] = {0, 0, 0};  // points returned in the first round, per caster
  // Ours on two threads, ours on one (the plugin's default), the baseline (one thread, no blocks).
  for (int config : {0, 1, 2}) {
    const bool blocks = config < 2;
    std::vector<LidarCaster> casters;
    const double mounts[3][4] = {{2.342, 0, 0.448, 0}, {1.549, 0.267, 0.543, 120}, {1.549, -0.267, 0.543, -120}};
    for (const auto& m : mounts) {
      LidarSpec s;
      s.mount = {m[0], m[1], m[2]};
      s.yaw = m[3] * M_PI / 180;
      s.elevations = row_elevations(32, -15, 15, "horizon", 2.0);
      s.use_blocks = blocks;
      s.coherent_columns = blocks;
      s.threads = config == 0 ? 2 : 1;
      casters.emplace_back(track, s);
    }
    std::vector<double> rates, frame_ms;
    PointBuffers buf;
    Rng rng(1);
    for (int round = 0; round < (quick ? 3 : 5); ++round) {
      std::size_t rays = 0;
      auto t0 = std::chrono::steady_clock::now();
      for (const auto& p : poses)
        for (const auto& c : casters) {
          buf.clear();
          rays += c.scan(p.T, p.seg, rng, 1.0, buf);
          if (round == 0) hits[config] += buf.x.size();
        }
      double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      rates.push_back(static_cast<double>(rays) / dt);
      frame_ms.push_back(dt * 1e3 / (poses.size() * casters.size()));
    }
    double r = median(rates), ms = median(frame_ms);
    // 3 frames (one per sensor) every 1/20 s of sim time.
    double rt = (1.0 / 20) / (3 * ms * 1e-3);
    const char* name[] = {"ours: blocks, columns, 2 threads", "  the same on one thread", "baseline: slab march only"};
    std::printf("%-34s %14.1f %12.3f %14.1f\n", name[config], r / 1e6, ms, rt);
    (config == 0 ? ours_rate : config == 1 ? one_thread_rate : base_rate) = r;
  }
  std::printf("ratio ours / baseline: %.2f (one thread: %.2f)\n\n", ours_rate / base_rate, one_thread_rate / base_rate);
  for (int config : {0, 1})
    if (std::abs(static_cast<double>(hits[config]) - static_cast<double>(hits[2])) > 1e-3 * static_cast<double>(hits[2]))
      return std::printf("the casters disagree: %zu points against the baseline's %zu on the same poses\n", hits[config], hits[2]), 1;

  // The full simulator graph, run by the host: the simulator alone (--no-report), and as a plain
  // `--out` run does, recording every wire but the clouds to SQLite (the recorder's
  // cost, shown beside). Runs alternate so that all see the same load.
  const std::string by = BRICKYARD_HOST;
  const double duration = quick ? 20 : 60;
  std::vector<double> factors, recorded, one_thread, stack, stack_one, stack_steady, stack_one_steady;
  // One run's sim and wall seconds. `race`: a race cut short by --duration fails as "did not
  // finish" and still measures; any other failure (a contact, a crash) does not.
  auto run = [&](const std::string& graph, const std::string& opts, double seconds, bool race, RunTimes& out) {
    const std::string dir = "/tmp/bench_sim_run";
    std::filesystem::remove_all(dir);  // no summary of an earlier run read as this one's
    const std::string cmd = by + " run " + src + "/configs/" + graph + " --duration " + std::to_string(seconds) + " --out " + dir +
                            " " + opts + " > /dev/null 2>&1";
    const int rc = std::system(cmd.c_str());
    std::ifstream f(dir + "/summary.json");
    const auto j = f ? nlohmann::json::parse(f, nullptr, false) : nlohmann::json();
    const std::string reason = j.is_object() ? j.value("reason", "") : "";
    const bool cut_short = race && reason.find("did not finish: ") != std::string::npos && reason.find("the run ended at") != std::string::npos;
    if (!j.is_object() || (rc != 0 && !cut_short)) {
      std::printf("run failed (exit %d%s%s): %s\n", rc, reason.empty() ? "" : ": ", reason.c_str(), cmd.c_str());
      return false;
    }
    out = {j["sim_time_s"].get<double>(), j["wall_time_s"].get<double>()};
    return true;
  };
  // The stack's factor twice: over the whole run (the start, planning the line and building the
  // road graph, included) and steady (the wall seconds of a 0.1 s run of the same graph taken off).
  auto stack_run = [&](const std::string& opts, std::vector<double>& whole, std::vector<double>& steady) {
    RunTimes full, start;
    if (!run("race.json", opts, duration, true, full) || !run("race.json", opts, 0.1, true, start)) return false;
    whole.push_back(full.sim_s / full.wall_s);
    steady.push_back((full.sim_s - start.sim_s) / (full.wall_s - start.wall_s));
    return true;
  };
  const std::string race = "--arg track=tracks/Spielberg.csv --arg wall_side=left --arg inner_wall=true --no-report";
  for (int i = 0; i < (quick ? 1 : 3); ++i) {
    // The simulator: as it runs, recording, on one thread; then the stack: as it runs, one thread.
    for (int mode : {0, 1, 2}) {
      RunTimes t;
      if (!run("sim_truth_lap.json", std::string("--set referee.laps=0") + (mode == 1 ? "" : " --no-report") + (mode == 2 ? " --threads 1" : ""),
               duration, false, t))
        return 1;
      (mode == 0 ? factors : mode == 1 ? recorded : one_thread).push_back(t.sim_s / t.wall_s);
    }
    if (!stack_run(race, stack, stack_steady) || !stack_run(race + " --threads 1", stack_one, stack_one_steady)) return 1;
  }
  std::printf("full simulator (configs/sim_truth_lap.json, %.0f s of sim time, %zu runs each)\n", duration, factors.size());
  std::printf("%-34s %14s\n", "", "x real time");
  std::printf("%-34s %14.1f\n", "ours: sim clock", median(factors));
  std::printf("%-34s %14.1f\n", "  the same, recording (--out)", median(recorded));
  std::printf("%-34s %14.1f\n", "  the same, on one thread", median(one_thread));
  std::printf("%-34s %14.1f\n", "baseline: real time", 1.0);
  std::printf("\nthe whole stack (configs/race.json, Spielberg, walls at both edges, %.0f s of sim time, %zu runs each);\n"
              "whole run: sim time over wall time; steady: the same less a 0.1 s run's (the start: line, road graph)\n",
              duration, stack.size());
  std::printf("%-34s %14s %14s\n", "", "whole run x RT", "steady x RT");
  std::printf("%-34s %14.1f %14.1f\n", "ours: sim clock", median(stack), median(stack_steady));
  std::printf("%-34s %14.1f %14.1f\n", "baseline: on one thread", median(stack_one), median(stack_one_steady));
  std::printf("%-34s %14.1f\n", "the simulator alone (above)", median(factors));
  std::printf("ratio ours / one thread: %.2f whole run, %.2f steady; ours (steady) / the simulator alone: %.2f\n",
              median(stack) / median(stack_one), median(stack_steady) / median(stack_one_steady), median(stack_steady) / median(factors));
  if (map.empty()) return 0;

  // The stack on its map: wall seconds of a run of `seconds`.
  auto wall_s = [&](const std::string& graph, const std::string& opts, double seconds, double& out) {
    RunTimes t;
    if (!run(graph, race + opts, seconds, true, t)) return false;
    out = t.wall_s;
    return true;
  };
  // race.json; on the map as it runs (GNSS taken: a frame in normal_interval_s); on the map
  // locating every frame, as through an outage.
  const std::string on_map = " --arg map_file=" + map;
  const std::string variants[3][2] = {{"race.json", ""}, {"race_on_map.json", on_map},
                                      {"race_on_map.json", on_map + " --set map_localizer.normal_interval_s=0"}};
  std::vector<double> f[3], ratio[2];
  for (int i = 0; i < (quick ? 1 : 5); ++i) {
    double x[3];
    for (int g = 0; g < 3; ++g) {
      double whole = 0, start = 0;
      if (!wall_s(variants[g][0], variants[g][1], duration, whole) || !wall_s(variants[g][0], variants[g][1], 0.1, start)) return 1;
      f[g].push_back(x[g] = (duration - 0.1) / (whole - start));
    }
    ratio[0].push_back(x[1] / x[0]), ratio[1].push_back(x[2] / x[0]);
  }
  std::printf("\nthe stack on its map (Spielberg, walls at both edges, %.0f s, %zu runs each, started)\n", duration, f[0].size());
  std::printf("%-44s %14s %14s\n", "", "x real time", "/ race.json");
  std::printf("%-44s %14.1f %14.2f\n", "ours: race_on_map.json", median(f[1]), median(ratio[0]));
  std::printf("%-44s %14.1f %14.2f\n", "  the same, every frame (as in an outage)", median(f[2]), median(ratio[1]));
  std::printf("%-44s %14.1f %14.2f\n", "baseline: race.json (no map)", median(f[0]), 1.0);
  return 0;
}
