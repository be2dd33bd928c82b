// A track mapped from a drive against the true one (docs/mapping.md): configs/map_ims.json
// run on each chosen track of a folder (data/tracks by default) — the full stack driving 2 laps at
// a moderate speed with the GNSS receivers' noise and the paper's double fault in one window — its
// scan mapper writing the track file it extracts from the drive; that file is then compared with
// the track file the simulator drove on: each mapped edge point's distance to the true edge, and
// the mapped banking against the simulator's. Prints per track p50 / p95 / max of the edges and
// of the banking, with the targets (p50 ≤ 0.10 m, p95 ≤ 0.25 m, banking within 0.5°).
// Then the race: configs/race.json, 2 laps at the car's limit, on the simulator's true track, once
// with the car's map from the true file and once from the mapped one (`--set map.track=…
// map.bank_mode=file`): the laps, lap times, wall contacts and least wall clearance of each.
// usage: eval_map_track [--tracks DIR] [--only NAME]... [--layout outer|both] [--seed N] [--jobs N]
//                       [--fault START] [--out DIR]
//        eval_map_track --mapped FILE --truth FILE [--bank-deg D]   (two files compared, no run;
//                       D: the truth banked by curvature, as IMS is)
//        eval_map_track --true-poses IMS [--offset D]   (no stack: the three LiDARs cast from the
//                       true poses along a line D m left of the centre line, every 2 m for one
//                       lap, the raw returns onto the road surface, the track extracted and compared: what the extraction
//                       does with a perfect localization)
// The mapped files stay in --out (default /tmp/eval_map_track): NAME/track.csv, NAME/map.pcd.
// Exit 1 when a run failed or a target was missed.
#include "mapping/common/scan_mapper.hpp"
#include "mapping/common/track_compare.hpp"
#include "mapping/common/track_extraction.hpp"
#include "perception_scenes.hpp"
#include "race_runs.hpp"
#include "track/banking.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  const std::string src = BRICKYARD_SOURCE_DIR, host = BRICKYARD_HOST;
  std::string tracks = src + "/data/tracks", layout = "outer", out = "/tmp/eval_map_track", fault = "50";
  std::vector<std::string> only;
  std::string mapped_file, truth_file, true_poses;
  double offset = 0;
  double bank_deg = 0;
  int seed = 0, jobs = 1;
  if (const int rc = brickyard::bench::check_option_pairs(argc, argv, "usage: eval_map_track [--tracks DIR] [--only NAME]... [--layout outer|both] [--seed N] [--jobs N] [--fault START] [--out DIR] eval_map_track --mapped FILE --truth FILE [--bank-deg D]   (two files compared, no run; D: the truth banked by curvature, as IMS is) eval_map_track --true-poses IMS [--offset D]   (no stack: the three LiDARs cast from the true poses along a line D m left of the centre line, every 2 m for one lap, the raw returns onto the road surface, the track extracted and compared: what the extraction does with a perfect localization)"); rc >= 0) return rc;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--tracks")) tracks = argv[i + 1];
    else if (!std::strcmp(argv[i], "--only")) only.push_back(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--layout")) layout = argv[i + 1];
    else if (!std::strcmp(argv[i], "--seed")) seed = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--jobs")) jobs = std::clamp(std::atoi(argv[i + 1]), 1, 16);
    else if (!std::strcmp(argv[i], "--fault")) fault = argv[i + 1];
    else if (!std::strcmp(argv[i], "--out")) out = argv[i + 1];
    else if (!std::strcmp(argv[i], "--mapped")) mapped_file = argv[i + 1];
    else if (!std::strcmp(argv[i], "--truth")) truth_file = argv[i + 1];
    else if (!std::strcmp(argv[i], "--bank-deg")) bank_deg = std::atof(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--true-poses")) true_poses = argv[i + 1];
    else if (!std::strcmp(argv[i], "--offset")) offset = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "eval_map_track: %s: unknown option\n", argv[i]);
      return 2;
    }
  }
  if ((argc - 1) % 2 != 0 || (layout != "outer" && layout != "both")) {
    std::fprintf(stderr, "usage: eval_map_track [--tracks DIR] [--only NAME]... [--layout outer|both] [--seed N] [--jobs N] "
                         "[--fault START] [--out DIR]\n");
    return 2;
  }
  if (!true_poses.empty()) {
    if (true_poses != "IMS") {
      std::fprintf(stderr, "eval_map_track: --true-poses: IMS only (the perception scenes' track)\n");
      return 2;
    }
    using namespace brickyard;
    scenes::ImsOptions o;
    const scenes::Ims ims(src + "/data", o);
    mapping::RoadSurface surface;
    std::vector<Eigen::Vector2d> driven;
    std::vector<double> roll;  // the car's, as the scan mapper gives its registered one
    const double L = ims.track().length();
    for (double s = 0; s <= L + 60; s += 2.0) {
      const scenes::Frame f = ims.frame(s, offset, static_cast<std::uint64_t>(s * 10) + 1);
      driven.emplace_back(f.world_from_body.translation().x(), f.world_from_body.translation().y());
      roll.push_back(mapping::roll_of(f.world_from_body));
      for (const auto& sc : f.scans)
        surface.add_scan(sc.x.data(), sc.y.data(), sc.z.data(), sc.intensity.data(), sc.x.size(), sc.vehicle_from_sensor,
                         f.world_from_body);
    }
    const mapping::ExtractedTrack t = mapping::extract_track(surface, driven, {}, &roll);
    const std::string file = out + "/true_poses_track.csv";
    fs::create_directories(out);
    track::write_centerline_csv(file, t.line);
    const auto truth = track::load_centerline_csv(src + "/data/tracks/IMS.csv");
    track::BankSpec bank;
    bank.mode = "curvature", bank.degrees = 9.2;
    bank.curvature_threshold = 1e-3;  // the perception scenes' IMS (perception_scenes.cpp)
    const auto c = mapping::compare_tracks(t.line, truth, track::bank_profile(truth, bank));
    std::printf("IMS from true poses, %.1f m left of the centre line (%s): edges p50 %.3f m, p95 %.3f m, max %.3f m "
                "(left p95 %.3f, right p95 %.3f); banking p50 %.2f°, p95 %.2f°, max %.2f°\n",
                offset, file.c_str(), c.edges.p50, c.edges.p95, c.edges.max, c.left.p95, c.right.p95, c.bank.p50, c.bank.p95,
                c.bank.max);
    return c.edges.p50 <= 0.10 && c.edges.p95 <= 0.25 && c.bank.max <= 0.5 ? 0 : 1;
  }
  if (!mapped_file.empty() || !truth_file.empty()) {
    try {
      const auto mapped = brickyard::track::load_centerline_csv(mapped_file);
      const auto truth = brickyard::track::load_centerline_csv(truth_file);
      brickyard::track::BankSpec bank;
      if (bank_deg != 0) bank.mode = "curvature", bank.degrees = bank_deg;
      const auto c = brickyard::mapping::compare_tracks(mapped, truth, brickyard::track::bank_profile(truth, bank));
      std::printf("edges: p50 %.3f m, p95 %.3f m, max %.3f m at s = %.0f m (left p95 %.3f, right p95 %.3f)\nbanking: p50 %.2f°, "
                  "p95 %.2f°, max %.2f° at s = %.0f m%s\n(s: along the true file from its first point)\n", c.edges.p50, c.edges.p95,
                  c.edges.max, c.edges_max_at_s, c.left.p95, c.right.p95, c.bank.p50, c.bank.p95, c.bank.max, c.bank_max_at_s,
                  c.reversed ? " (mapped the other way round)" : "");
      return c.edges.p50 <= 0.10 && c.edges.p95 <= 0.25 && c.bank.max <= 0.5 ? 0 : 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "eval_map_track: %s\n", e.what());
      return 2;
    }
  }
  std::vector<brickyard::bench::TrackFile> files;
  for (auto& tf : brickyard::bench::track_files(tracks))
    if (only.empty() || std::find(only.begin(), only.end(), tf.name) != only.end()) files.push_back(std::move(tf));
  if (files.empty()) {
    std::fprintf(stderr, "eval_map_track: no track chosen in %s\n", tracks.c_str());
    return 2;
  }
  fs::create_directories(out);
  const std::string graph = src + "/configs/map_ims.json";
  std::vector<brickyard::bench::RaceRun> runs(files.size()), on_truth(files.size()), on_map(files.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&](int domain) {
    for (std::size_t k; (k = next++) < files.size();) {
      const auto& tf = files[k];
      if (!tf.error.empty()) continue;
      const std::string dir = out + "/" + tf.name;
      fs::create_directories(dir);
      std::vector<std::string> a = brickyard::bench::track_args(tf.path, tf.name, tf.line, layout == "both");
      const double fs0 = std::atof(fault.c_str());
      a.insert(a.end(), {"laps=2", "duration=900", "fault_start=" + fault, "fault_end=" + std::to_string(fs0 + 10),
                         "map_file=" + dir + "/map.pcd", "track_file=" + dir + "/track.csv"});
      std::remove((dir + "/track.csv").c_str());  // an earlier run's file must not stand for this one's
      runs[k] = brickyard::bench::run_race(host, graph, a, {}, seed, dir + "/run", domain);
      if (!runs[k].ok) continue;
      const std::vector<std::string> race_args = brickyard::bench::track_args(tf.path, tf.name, tf.line, layout == "both");
      const std::string race_graph = src + "/configs/race.json";
      on_truth[k] = brickyard::bench::run_race(host, race_graph, race_args, {}, seed, dir + "/race_true", domain);
      on_map[k] = brickyard::bench::run_race(host, race_graph, race_args, {"map.track=" + dir + "/track.csv", "map.bank_mode=file"}, seed,
                                             dir + "/race_mapped", domain);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < jobs; ++j) pool.emplace_back(worker, 170 + j);
  for (auto& th : pool) th.join();
  std::printf("| track | walls | edges p50 | p95 | max (at s) | left p95 | right p95 | banking p50 | p95 | max (at s) | targets |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  bool all_ok = true;
  for (std::size_t k = 0; k < files.size(); ++k) {
    const auto& tf = files[k];
    const std::string dir = out + "/" + tf.name;
    if (!tf.error.empty() || !runs[k].ok) {
      std::printf("| %s | %s | run failed: %s |\n", tf.name.c_str(), layout.c_str(),
                  tf.error.empty() ? runs[k].reason.c_str() : tf.error.c_str());
      all_ok = false;
      continue;
    }
    try {
      const brickyard::track::CenterLine mapped = brickyard::track::load_centerline_csv(dir + "/track.csv");
      brickyard::track::BankSpec bank;  // as track_args gives the simulator
      if (tf.name == "IMS") bank.mode = "curvature", bank.degrees = 9.2;
      const auto c = brickyard::mapping::compare_tracks(mapped, tf.line, brickyard::track::bank_profile(tf.line, bank));
      const bool met = c.edges.p50 <= 0.10 && c.edges.p95 <= 0.25 && c.bank.max <= 0.5;
      all_ok = all_ok && met;
      std::printf("| %s | %s | %.3f m | %.3f m | %.3f m at %.0f m | %.3f m | %.3f m | %.2f° | %.2f° | %.2f° at %.0f m | %s |\n",
                  tf.name.c_str(), layout.c_str(), c.edges.p50, c.edges.p95, c.edges.max, c.edges_max_at_s, c.left.p95, c.right.p95,
                  c.bank.p50, c.bank.p95, c.bank.max, c.bank_max_at_s, met ? "met" : "not met");
    } catch (const std::exception& e) {
      std::printf("| %s | %s | %s |\n", tf.name.c_str(), layout.c_str(), e.what());
      all_ok = false;
    }
  }
  std::printf("\n| track | walls | car's map | race | lap times | wall contacts | least wall clearance | planned lap |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (!runs[k].ok) continue;
    for (int m = 0; m < 2; ++m) {
      const brickyard::bench::RaceRun& r = m ? on_map[k] : on_truth[k];
      std::string laps;
      if (r.referee.contains("lap_times_s"))
        for (const auto& x : r.referee["lap_times_s"]) {
          char b[32];
          std::snprintf(b, sizeof b, "%s%.2f s", laps.empty() ? "" : ", ", x.get<double>());
          laps += b;
        }
      std::printf("| %s | %s | %s | %s | %s | %.0f | %.2f m | %.2f s |\n", files[k].name.c_str(), layout.c_str(),
                  m ? "mapped" : "true file", r.ok ? "finished" : r.reason.c_str(), laps.c_str(),
                  brickyard::bench::metric(r.referee, "wall_contacts"), brickyard::bench::metric(r.referee, "min_wall_clearance_m"),
                  brickyard::bench::metric(r.planner, "planned_lap_s"));
      all_ok = all_ok && r.ok;
    }
  }
  return all_ok ? 0 : 1;
}
