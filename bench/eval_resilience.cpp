// The resilience evaluation of the paper's headline (both GNSS receivers degraded while
// the car is in a turn at speed) on the full stack of configs/ims_resilient.json, swept over the
// speed (40 m/s, the paper's top speed; 60; 80) and the fault's length (3, 7, 15 s), beside the
// same graph without the system manager (the path tracker on the resilient estimate alone) and
// with the naive filter (no resilience: it fuses the bad fixes). The fault starts as
// the car enters turn 1 (s = 350 m); each run goes on 20 s past it. Prints the table of
// docs/results-resilience.md.
// usage: eval_resilience [--seed N]
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

std::string fault(double start, double end, double dx, double dy) {
  json f = json::array();
  f.push_back({{"type", "bias"}, {"start_s", start}, {"end_s", end}, {"offset", {dx, dy, 0}}});
  f.push_back({{"type", "noise"}, {"start_s", start}, {"end_s", end}, {"factor", 30}});
  return f.dump();
}

}  // namespace

int main(int argc, char** argv) {
  int seed = 1;
  if (argc > 2 && std::strcmp(argv[1], "--seed") == 0) seed = std::atoi(argv[2]);
  const std::string src = BRICKYARD_SOURCE_DIR, by = BRICKYARD_HOST, dir = "/tmp/eval_resilience";
  std::filesystem::create_directories(dir);
  std::ifstream in(src + "/configs/ims_resilient.json");
  const json base = json::parse(in);
  std::printf("| speed | fault | stack | outcome | wall contacts | track violations | min wall clearance | wall follower | safe stop | back on the path | max localization error |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (double v : {40.0, 60.0, 80.0})
    for (double length : {3.0, 7.0, 15.0})
      for (const char* stack : {"resilient", "no manager", "naive"}) {
        json g = base;
        const double start = 350.0 / v, end = start + length;
        g["nodes"]["car"]["params"]["start_speed"] = v;
        g["nodes"]["racing_line"]["params"]["v_max"] = v;
        g["nodes"]["gnss_left"]["params"]["faults"] = json::parse(fault(start, end, 6, -8));
        g["nodes"]["gnss_right"]["params"]["faults"] = json::parse(fault(start, end, 5, -9));
        g["nodes"]["referee"]["params"] = json::object();
        g["clock"]["duration_s"] = end + 20;
        if (std::strcmp(stack, "naive") == 0) g["nodes"]["estimator"]["plugin"] = "estimation.ekf_naive";
        if (std::strcmp(stack, "no manager") == 0) {
          // The path tracker drives on the resilient estimate alone (dead reckoning through the
          // fault): the manager and the wall follower are taken out and their wires with them.
          g["nodes"].erase("manager");
          g["nodes"].erase("wall_follower");
          json wires = json::array();
          for (auto w : g["wires"]) {
            const std::string from = w["from"];
            if (from.rfind("manager.", 0) == 0 || from.rfind("wall_follower.", 0) == 0 || from.rfind("path_tracker.", 0) == 0 ||
                from == "estimator.mode")
              continue;
            json to = json::array();
            for (const auto& t : w["to"].is_array() ? w["to"] : json::array({w["to"]})) {
              const std::string dest = t;
              if (dest.rfind("manager.", 0) != 0 && dest.rfind("wall_follower.", 0) != 0) to.push_back(dest);
            }
            if (to.empty()) continue;
            w["to"] = to;
            wires.push_back(w);
          }
          wires.push_back({{"from", "path_tracker.command"}, {"to", "car.command"}});
          g["wires"] = wires;
        }
        std::ofstream(dir + "/graph.json") << g.dump(1);
        const std::string cmd = by + " run " + dir + "/graph.json --quiet --seed " + std::to_string(seed) + " --out " + dir +
                                "/run > " + dir + "/run.log 2>&1";
        const int rc = std::system(cmd.c_str());
        std::ifstream sf(dir + "/run/summary.json");
        if (!sf) {
          std::fprintf(stderr, "no summary (exit %d): see %s/run.log\n", rc, dir.c_str());
          return 1;
        }
        const json s = json::parse(sf);
        const json& r = s["nodes"]["referee"]["metrics"];
        auto num = [](const json& m, const char* k) { return m.contains(k) && m[k].is_number() ? m[k].get<double>() : NAN; };
        std::string outcome = s["result"] == "success" ? "drove on" : s.value("reason", std::string("failed"));
        const auto at = outcome.find("crash: ");
        if (at != std::string::npos) outcome = outcome.substr(at);
        std::string wall = "—", stop = "—", back = "—";
        if (s["nodes"].contains("manager")) {
          const json& m = s["nodes"]["manager"]["metrics"];
          char b[64];
          const bool left_path = num(m, "entered_WALL_FOLLOW") > 0 || num(m, "entered_SAFE_STOP") > 0;
          std::snprintf(b, sizeof b, "%.1f s", num(m, "time_s_WALL_FOLLOW"));
          if (num(m, "entered_WALL_FOLLOW") > 0) wall = b;
          std::snprintf(b, sizeof b, "%.1f s", num(m, "time_s_SAFE_STOP"));
          if (num(m, "entered_SAFE_STOP") > 0) stop = b;
          if (left_path) back = num(m, "entered_PATH") > 0 ? "yes" : "no";
        }
        std::printf("| %.0f m/s | %.0f s | %s | %s | %.0f | %.0f | %.2f m | %s | %s | %s | %.2f m |\n", v, length, stack, outcome.c_str(),
                    num(r, "wall_contacts"), num(r, "track_violations"), num(r, "min_wall_clearance_m"), wall.c_str(), stop.c_str(),
                    back.c_str(), num(r, "localization_max_error_m"));
        std::fflush(stdout);
      }
  return 0;
}
