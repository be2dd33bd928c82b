#include "race_runs.hpp"

#include <cstdio>
#include <cstring>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdlib>
#include <fstream>

namespace brickyard::bench {

namespace {
// Shell-quoted, for std::system.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

double metric(const nlohmann::json& m, const char* k) { return m.contains(k) && m[k].is_number() ? m[k].get<double>() : NAN; }

RaceRun run_race(const std::string& host, const std::string& graph, const std::vector<std::string>& args,
                 const std::vector<std::string>& sets, int seed, const std::string& dir, int domain) {
  std::string cmd = host + " run " + quoted(graph) + " --quiet --progress 0 --no-report --seed " + std::to_string(seed) +
                    " --domain " + std::to_string(domain) + " --out " + quoted(dir);
  for (const auto& a : args) cmd += " --arg " + quoted(a);
  for (const auto& a : sets) cmd += " --set " + quoted(a);
  // The run's own command beside its log: any row of a sweep is rerun by hand from it.
  std::ofstream(dir + ".cmd") << cmd << "\n";
  cmd += " > " + quoted(dir + ".log") + " 2>&1";
  // A summary left by an earlier sweep must not stand for a run that never wrote one.
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::system(cmd.c_str());
  RaceRun r;
  std::ifstream sf(dir + "/summary.json");
  if (!sf) {
    r.reason = "no summary: see " + dir + ".log";
    return r;
  }
  const nlohmann::json s = nlohmann::json::parse(sf, nullptr, false);
  if (s.is_discarded() || !s.contains("nodes")) {
    r.reason = "unreadable summary: see " + dir + ".log";
    return r;
  }
  r.ok = s.value("result", "") == "success";
  r.reason = s.value("reason", "");
  r.sim_s = s.value("sim_time_s", 0.0);
  r.wall_s = s.value("wall_time_s", 0.0);
  const auto& nodes = s["nodes"];
  if (nodes.contains("referee")) r.referee = nodes["referee"]["metrics"];
  if (nodes.contains("manager")) r.manager = nodes["manager"]["metrics"];
  if (nodes.contains("planner")) r.planner = nodes["planner"]["metrics"];
  r.nodes = nlohmann::json::object();
  for (const auto& [name, node] : nodes.items()) r.nodes[name] = node.contains("metrics") ? node["metrics"] : nlohmann::json::object();
  return r;
}

std::vector<TrackFile> track_files(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> paths;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".csv") paths.push_back(fs::absolute(e.path()));
  std::sort(paths.begin(), paths.end());
  std::vector<TrackFile> out;
  for (const auto& f : paths) {
    TrackFile t{f.string(), f.stem().string(), {}, {}};
    try {
      t.line = track::load_centerline_csv(t.path);
    } catch (const std::exception& e) {
      t.error = e.what();
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<std::string> track_args(const std::string& file, const std::string& name, const track::CenterLine& c,
                                    bool both_walls) {
  std::vector<std::string> a = {"track=" + file, std::string("wall_side=") + (track::counter_clockwise(c) ? "right" : "left"),
                                std::string("inner_wall=") + (both_walls ? "true" : "false")};
  // Always said: a graph's own default may differ (configs/map_ims.json banks every curve, as IMS is).
  if (name == "IMS") a.insert(a.end(), {"bank_mode=curvature", "bank_deg=9.2"});
  else a.insert(a.end(), {"bank_mode=none", "bank_deg=0"});
  return a;
}

int check_option_pairs(int argc, char** argv, const char* usage) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return std::printf("%s\n", usage), 0;
  if (argc % 2 == 0) return std::fprintf(stderr, "%s: needs a value\n%s\n", argv[argc - 1], usage), 2;
  return -1;
}

}  // namespace brickyard::bench
