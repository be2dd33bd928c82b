// Issue 7's obstacle scenario (docs/planning.md): configs/ims_obstacles.json — two sets of two
// pylons on the IMS front straight, one timed lap on the full stack — with planning.road_graph at
// 31 m/s (the floor; the paper passed at 111.4 km/h) and 50 m/s, each beside the same lap
// with no pylons (the time the avoidance costs), and with planning.racing_line in the planner's
// place (the one-line swap). Prints the table of docs/planning.md.
// usage: eval_obstacles [--seed N]
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

using nlohmann::json;

struct Outcome {
  std::string result;
  double lap = NAN, clearance = NAN, wall = NAN, top = NAN, hits = NAN, offset = NAN, violations = NAN;
};

Outcome run(const json& g, const std::string& dir, int seed) {
  std::ofstream(dir + "/graph.json") << g.dump(1);
  const std::string cmd = std::string(BRICKYARD_HOST) + " run " + dir + "/graph.json --quiet --seed " + std::to_string(seed) +
                          " --out " + dir + "/run > " + dir + "/run.log 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream sf(dir + "/run/summary.json");
  Outcome o;
  if (!sf) {
    o.result = "no summary (exit " + std::to_string(rc) + ")";
    return o;
  }
  const json s = json::parse(sf);
  const json& r = s["nodes"]["referee"]["metrics"];
  auto num = [](const json& m, const char* k) { return m.contains(k) && m[k].is_number() ? m[k].get<double>() : NAN; };
  o.result = s["result"] == "success" ? "lap completed" : s.value("reason", std::string("failed"));
  if (r.contains("lap_times_s") && !r["lap_times_s"].empty()) o.lap = r["lap_times_s"][0].get<double>();
  o.clearance = num(r, "obstacle_min_clearance_m");
  o.wall = num(r, "min_wall_clearance_m");
  o.top = num(r, "max_speed_mps");
  o.hits = num(r, "obstacles_hit");
  o.violations = num(r, "track_violations");
  if (s["nodes"]["planner"].contains("metrics")) o.offset = num(s["nodes"]["planner"]["metrics"], "max_offset_from_line_m");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  int seed = 1;
  if (argc > 2 && std::strcmp(argv[1], "--seed") == 0) seed = std::atoi(argv[2]);
  const std::string src = BRICKYARD_SOURCE_DIR, dir = "/tmp/eval_obstacles";
  std::filesystem::create_directories(dir);
  std::ifstream in(src + "/configs/ims_obstacles.json");
  const json base = json::parse(in);
  std::printf("| planner | speed | pylons hit | least pylon clearance | lap time | clean lap | time lost | least wall clearance | track violations | top speed | most offset from the line |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* planner : {"planning.road_graph", "planning.racing_line"})
    for (double v : {31.0, 50.0}) {
      json g = base;
      g["nodes"]["planner"]["plugin"] = planner;
      g["nodes"]["planner"]["params"]["v_max"] = v;
      g["nodes"]["car"]["params"]["start_speed"] = v;
      json clean = g;
      clean["nodes"]["world"]["params"]["pylons"] = json::array();
      const Outcome a = run(g, dir, seed), c = run(clean, dir, seed);
      const bool road = std::strcmp(planner, "planning.road_graph") == 0;
      char off[32] = "—";
      if (road) std::snprintf(off, sizeof off, "%.1f m", a.offset);
      std::printf("| %s | %.0f m/s | %.0f | %.2f m | %.2f s | %.2f s | %+.2f s | %.2f m | %.0f | %.1f m/s | %s |\n", planner, v,
                  a.hits, a.clearance, a.lap, c.lap, a.lap - c.lap, a.wall, a.violations, a.top, off);
      if (a.result != "lap completed") std::printf("| | | %s | | | | | | | | |\n", a.result.c_str());
      std::fflush(stdout);
    }
  return 0;
}
