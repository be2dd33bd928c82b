// Issue 41's sweep (docs/results-gnss-faults.md): the car racing on its track's prior map
// (configs/eval/gnss_faults.json: configs/race_on_map.json with its localization scored against
// the truth) through GNSS faults, on every track in a folder, for both wall layouts. Per track and
// layout: the track's map from a mapping drive (scripts/track-map, cached under --maps), a clean
// race (the map must neither refuse nor overrule its healthy GNSS), then each fault class for
// each duration at --placements evenly spaced starts in lap 2 ("laps": the whole of laps 2 and
// 3). A row per track, layout, class and duration: runs that finished clean, contacts,
// violations, least wall clearance, the slowest lap against the clean run's same lap,
// localization error p99 and max (the worst run), the time the fusion took to flag the fault,
// the longest time in each mode; "ok" or what missed the issue's target.
// usage: eval_gnss_faults [--tracks DIR] [--track NAME]... [--layout outer|both] [--faults a,b]
//                         [--durations 7,60,laps] [--placements N] [--seed N] [--jobs N]
//                         [--domain N] [--maps DIR] [--brickyard HOST] [--set NODE.PARAM=V]...
// --brickyard: the host that races (default this build's); a copy of bin/brickyard with its lib/
// beside it lets the build go on while a sweep runs.
// Runs and maps go under $EVAL_GNSS_FAULTS_DIR (default /tmp/eval_gnss_faults). Exit 1 when any
// row missed its target, 2 on a bad option.
#include "race_runs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using nlohmann::json;
using brickyard::bench::RaceRun;
namespace fs = std::filesystem;

double num(const json& m, const char* k) { return brickyard::bench::metric(m, k); }
const json& node(const RaceRun& r, const char* name) {
  static const json none = json::object();
  return r.nodes.contains(name) ? r.nodes[name] : none;
}

// A run's lap times: empty when its referee said nothing (the run did not start).
json lap_times(const RaceRun& r) { return r.referee.is_object() ? r.referee.value("lap_times_s", json::array()) : json::array(); }
std::string final_mode(const RaceRun& r) { return r.manager.is_object() ? r.manager.value("final_mode", "") : ""; }

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// A fault window's JSON, each receiver's, and the LiDARs' (lidar_loss).
std::string window(const char* type, double start, double end, const std::string& extra = "") {
  char b[256];
  std::snprintf(b, sizeof b, R"({"type":"%s","start_s":%.3f,"end_s":%.3f%s})", type, start, end, extra.c_str());
  return b;
}

// The fault classes: each receiver's faults (both always set: race.json's own are the paper's),
// and the LiDARs'. A bias claims RTK-fixed (fix_type 3) while it lasts.
const std::vector<std::string> kClasses = {"dropout", "bias_both", "bias_one", "drift_both", "freeze_both", "paper", "lidar_loss"};

std::vector<std::string> fault_sets(const std::string& cls, double start, double end) {
  const std::string bias = "[" + window("bias", start, end, R"(,"offset":[6,-8,0],"fix_type":3)") + "]";
  const std::string drift = "[" + window("drift", start, end, R"(,"rate":[0.2,-0.2,0],"fix_type":3)") + "]";
  const std::string dropout = "[" + window("dropout", start, end) + "]";
  const std::string frozen = "[" + window("freeze", start, end, R"(,"fix_type":3)") + "]";
  auto gnss = [](const std::string& left, const std::string& right) {
    return std::vector<std::string>{"gnss_left.faults=" + left, "gnss_right.faults=" + right};
  };
  if (cls == "dropout") return gnss(dropout, dropout);
  if (cls == "bias_both") return gnss(bias, bias);
  if (cls == "bias_one") return gnss(bias, "[]");
  if (cls == "drift_both") return gnss(drift, drift);
  if (cls == "freeze_both") return gnss(frozen, frozen);
  if (cls == "paper") return {};
  // lidar_loss: GNSS gone for the window, and every LiDAR's frames lost for 3 s in its middle.
  std::vector<std::string> s = gnss(dropout, dropout);
  const double mid = 0.5 * (start + end);
  const std::string lost = "[" + window("frame_loss", mid - 1.5, mid + 1.5, R"(,"probability":1)") + "]";
  for (const char* l : {"lidar_front", "lidar_left", "lidar_right"}) s.push_back(std::string(l) + ".faults=" + lost);
  return s;
}

struct Options {
  std::string tracks, only_layout, maps, host = BRICKYARD_HOST;
  std::vector<std::string> names, classes = {"dropout", "bias_both", "bias_one", "lidar_loss"}, durations = {"60", "laps"};
  std::vector<std::string> sets;
  int placements = 2, seed = 0, jobs = 1, domain0 = 150;
};

// One run's figures that a row takes the worst of.
struct Figures {
  bool clean = false;
  double contacts = 0, violations = 0, clearance = 1e9, lap_ratio = 0, p99 = 0, max = 0, detect = NAN;
  double warning = 0, emergency = 0, wall = 0, stop = 0;
  std::string why;
};

Figures figures(const RaceRun& r, const RaceRun& clean, double start) {
  Figures f;
  f.contacts = num(r.referee, "wall_contacts");
  f.violations = num(r.referee, "track_violations");
  f.clearance = num(r.referee, "min_wall_clearance_m");
  f.clean = r.ok && f.contacts == 0 && f.violations == 0 && final_mode(r) == "PATH";
  if (!f.clean) f.why = r.ok ? "contact, violation or not back on the path" : r.reason;
  const json laps = lap_times(r), base = lap_times(clean);
  for (std::size_t k = 1; k < laps.size() && k < base.size(); ++k)
    f.lap_ratio = std::max(f.lap_ratio, laps[k].get<double>() / base[k].get<double>());
  const json& score = node(r, "score");
  f.p99 = num(score, "p99_error_m");
  f.max = num(score, "max_error_m");
  const json& est = node(r, "estimator");
  // The bias found: the fusion's first status other than NORMAL from the fault's start (the
  // scorer's time to flag: fixes refused, by the map or the paper's rule). -1: never.
  f.detect = num(score, "time_to_flag_s");
  f.warning = num(est, "time_warning_s");
  f.emergency = num(est, "time_emergency_s");
  f.wall = num(r.manager, "time_s_WALL_FOLLOW");
  f.stop = num(r.manager, "time_s_SAFE_STOP");
  return f;
}

// The issue's targets for a class: what a row missed, empty when none.
std::string missed(const std::string& cls, const Figures& w, int runs, int clean) {
  std::string m;
  if (clean < runs) m += " " + std::to_string(runs - clean) + " run(s) not clean;";
  if ((cls == "dropout" || cls == "bias_one") && w.lap_ratio > 1.03) m += " a lap over 1.03x the clean one;";
  if (cls == "dropout" && (w.p99 > 0.3 || w.max > 0.5)) m += " error over p99 0.3 m / max 0.5 m;";
  if (cls == "bias_both" && !(w.detect >= 0 && w.detect <= 1.0)) m += " bias not found within 1 s;";
  if (cls == "bias_both" && w.max > 0.5) m += " error over 0.5 m;";
  return m;
}

Figures worst(const std::vector<Figures>& all) {
  Figures w;
  for (const Figures& f : all) {
    w.contacts += f.contacts;
    w.violations += f.violations;
    w.clearance = std::min(w.clearance, f.clearance);
    w.lap_ratio = std::max(w.lap_ratio, f.lap_ratio);
    w.p99 = std::max(w.p99, f.p99);
    w.max = std::max(w.max, f.max);
    w.warning = std::max(w.warning, f.warning);
    w.emergency = std::max(w.emergency, f.emergency);
    w.wall = std::max(w.wall, f.wall);
    w.stop = std::max(w.stop, f.stop);
    if (!f.why.empty()) w.why += " " + f.why + ";";
    if (std::isnan(w.detect)) w.detect = f.detect;
    else if (f.detect < 0 || w.detect < 0) w.detect = -1;  // a run never flagged it
    else w.detect = std::max(w.detect, f.detect);
  }
  return w;
}

// The fault windows of a duration: --placements starts spread over lap 2 (7 s, 60 s), or the
// whole of laps 2 and 3 ("laps").
std::vector<std::pair<double, double>> windows(const std::string& duration, const json& laps, int placements) {
  const double lap1 = laps[0].get<double>(), lap2 = laps[1].get<double>();
  if (duration == "laps") return {{lap1, lap1 + lap2 + laps[2].get<double>()}};
  const double length = std::atof(duration.c_str());
  std::vector<std::pair<double, double>> w;
  for (int k = 0; k < placements; ++k) {
    const double start = lap1 + (k + 0.5) / placements * lap2;
    w.emplace_back(start, start + length);
  }
  return w;
}

// The runs of one row, --jobs at a time, each on a domain of its own.
std::vector<RaceRun> run_all(const Options& o, const std::string& by, const std::string& graph, const std::vector<std::vector<std::string>>& args,
                             const std::vector<std::vector<std::string>>& sets, const std::vector<std::string>& dirs) {
  std::vector<RaceRun> out(args.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&](int domain) {
    for (std::size_t k; (k = next++) < args.size();) out[k] = brickyard::bench::run_race(by, graph, args[k], sets[k], o.seed, dirs[k], domain);
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < o.jobs; ++j) pool.emplace_back(worker, o.domain0 + 1 + j);
  for (auto& th : pool) th.join();
  return out;
}

std::string detect_text(double d) {
  char b[48];
  if (std::isnan(d)) return "–";
  if (d < 0) return "never";
  std::snprintf(b, sizeof b, "%.2f s", d);
  return b;
}

// How honest the map's poses were: their errors weighed by their own covariances (map_score). On
// stderr: the table on stdout stays a table.
void print_map_honesty(const std::string& what, const RaceRun& r) {
  const json& m = node(r, "map_score");
  std::fprintf(stderr, "%s: map poses %.0f, error p99 %.2f m max %.2f m, NEES p99 %.1f, over 13.8 in %.2f %%, largest error where sure to 0.5 m: %.2f m\n",
              what.c_str(), num(m, "judged"), num(m, "p99_error_m"), num(m, "max_error_m"), num(m, "nees_p99"), 100 * num(m, "overconfident_share"),
              num(m, "max_error_sure_m"));
}

// One row: every placement of one class and duration.
bool fault_row(const Options& o, const std::string& by, const std::string& graph, const std::string& tag, const std::vector<std::string>& base,
               const RaceRun& clean, const std::string& cls, const std::string& duration) {
  const json laps = lap_times(clean);
  std::vector<std::vector<std::string>> args, sets;
  std::vector<std::string> dirs;
  const auto wins = windows(duration, laps, o.placements);
  for (std::size_t k = 0; k < wins.size(); ++k) {
    std::vector<std::string> a = base;
    char b[64];
    std::snprintf(b, sizeof b, "fault_start=%.3f", wins[k].first);
    a.push_back(b);
    std::snprintf(b, sizeof b, "fault_end=%.3f", wins[k].second);
    a.push_back(b);
    a.push_back(duration == "laps" ? "laps=4" : "laps=3");
    args.push_back(a);
    std::vector<std::string> s = fault_sets(cls, wins[k].first, wins[k].second);
    s.insert(s.end(), o.sets.begin(), o.sets.end());
    sets.push_back(s);
    dirs.push_back(tag + "_" + cls + "_" + duration + "_" + std::to_string(k));
  }
  const std::vector<RaceRun> runs = run_all(o, by, graph, args, sets, dirs);
  std::vector<Figures> all;
  int clean_runs = 0;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    print_map_honesty(dirs[k], runs[k]);
    all.push_back(figures(runs[k], clean, wins[k].first));
    clean_runs += all.back().clean;
  }
  const Figures w = worst(all);
  const std::string miss = missed(cls, w, static_cast<int>(runs.size()), clean_runs);
  std::printf("| %s | %s s | %d of %zu | %.0f | %.0f | %.2f m | %.3f× | %.2f / %.2f m | %s | %.1f / %.1f s | %.1f / %.1f s | %s |\n", cls.c_str(),
              duration.c_str(), clean_runs, runs.size(), w.contacts, w.violations, w.clearance, w.lap_ratio, w.p99, w.max, detect_text(w.detect).c_str(),
              w.warning, w.emergency, w.wall, w.stop, miss.empty() ? "ok" : ("FAIL:" + miss + w.why).c_str());
  std::fflush(stdout);
  return miss.empty();
}

int parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; i += 2) {
    const std::string k = argv[i];
    if (i + 1 >= argc) return std::fprintf(stderr, "eval_gnss_faults: %s: needs a value\n", k.c_str()), 2;
    const char* v = argv[i + 1];
    if (k == "--tracks") o.tracks = v;
    else if (k == "--track") o.names.push_back(v);
    else if (k == "--layout") o.only_layout = v;
    else if (k == "--faults") o.classes = split(v);
    else if (k == "--durations") o.durations = split(v);
    else if (k == "--placements") o.placements = std::clamp(std::atoi(v), 1, 50);
    else if (k == "--seed") o.seed = std::atoi(v);
    else if (k == "--jobs") o.jobs = std::clamp(std::atoi(v), 1, 16);
    else if (k == "--domain") o.domain0 = std::clamp(std::atoi(v), 0, 200);
    else if (k == "--maps") o.maps = v;
    else if (k == "--brickyard") o.host = v;
    else if (k == "--set") o.sets.push_back(v);
    else return std::fprintf(stderr, "eval_gnss_faults: %s: unknown option\n", k.c_str()), 2;
  }
  for (const auto& c : o.classes)
    if (std::find(kClasses.begin(), kClasses.end(), c) == kClasses.end())
      return std::fprintf(stderr, "eval_gnss_faults: --faults: %s: not one of dropout, bias_both, bias_one, drift_both, freeze_both, paper, lidar_loss\n", c.c_str()), 2;
  for (const auto& d : o.durations)
    if (d != "laps" && !(std::atof(d.c_str()) > 0)) return std::fprintf(stderr, "eval_gnss_faults: --durations: %s: seconds or laps\n", d.c_str()), 2;
  if (!o.only_layout.empty() && o.only_layout != "outer" && o.only_layout != "both")
    return std::fprintf(stderr, "eval_gnss_faults: --layout: %s: outer or both\n", o.only_layout.c_str()), 2;
  return 0;
}

// The track's map, made by its mapping drive with the race's own world arguments (cached).
bool track_map(const std::string& src, const std::string& by, const std::vector<std::string>& base, const std::string& dir) {
  std::string cmd = "BY='" + by + "' '" + src + "/scripts/track-map' '" + base[0].substr(6) + "' '" + dir + "'";
  for (std::size_t i = 1; i < base.size(); ++i) cmd += " --arg '" + base[i] + "'";
  return std::system((cmd + " > '" + dir + ".log' 2>&1").c_str()) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string src = BRICKYARD_SOURCE_DIR;
  Options o;
  o.tracks = src + "/data/tracks";
  if (const int rc = parse(argc, argv, o)) return rc;
  if (!fs::is_regular_file(o.host)) return std::fprintf(stderr, "eval_gnss_faults: --brickyard: %s: not a file\n", o.host.c_str()), 2;
  const std::string by = o.host;
  const std::string dir = std::getenv("EVAL_GNSS_FAULTS_DIR") ? std::getenv("EVAL_GNSS_FAULTS_DIR") : "/tmp/eval_gnss_faults";
  if (o.maps.empty()) o.maps = dir + "/maps";
  fs::create_directories(dir);
  fs::create_directories(o.maps);
  const std::string graph = src + "/configs/eval/gnss_faults.json";
  bool all_ok = true;
  for (const auto& tf : brickyard::bench::track_files(o.tracks)) {
    if (!o.names.empty() && std::find(o.names.begin(), o.names.end(), tf.name) == o.names.end()) continue;
    if (!tf.error.empty()) {
      std::printf("%s: %s\n", tf.name.c_str(), tf.error.c_str());
      all_ok = false;
      continue;
    }
    for (const char* layout : {"outer", "both"}) {
      if (!o.only_layout.empty() && o.only_layout != layout) continue;
      std::vector<std::string> base = brickyard::bench::track_args(tf.path, tf.name, tf.line, std::strcmp(layout, "both") == 0);
      const std::string tag = dir + "/" + tf.name + "_" + layout, map = o.maps + "/" + tf.name + "_" + layout;
      std::printf("\n%s, %s wall%s:\n", tf.name.c_str(), layout, std::strcmp(layout, "both") ? "" : "s");
      std::fflush(stdout);
      if (!track_map(src, by, base, map)) {
        std::printf("the mapping drive failed: %s.log\n", map.c_str());
        all_ok = false;
        continue;
      }
      base.push_back("map_file=" + map + "/map.pcd");
      std::vector<std::string> clean_args = base;
      clean_args.insert(clean_args.end(), {"fault_start=1000000", "fault_end=1000001"});
      clean_args.push_back(std::find(o.durations.begin(), o.durations.end(), "laps") != o.durations.end() ? "laps=4" : "laps=3");
      const RaceRun clean = brickyard::bench::run_race(by, graph, clean_args, o.sets, o.seed, tag + "_clean", o.domain0);
      const json laps = lap_times(clean);
      const json& est = node(clean, "estimator");
      std::printf("clean: %s, laps %s, planned %.2f s, map verified %.0f, fixes refused by the map %.0f, overruled by it %.0f, error p99 %.2f m max %.2f m, real time %.1f×\n\n",
                  clean.ok ? "finished" : clean.reason.c_str(), laps.dump().c_str(), num(clean.planner, "planned_lap_s"), num(est, "map_verified"),
                  num(est, "fixes_refused_by_map"), num(est, "map_overrulings"), num(node(clean, "score"), "p99_error_m"), num(node(clean, "score"), "max_error_m"),
                  clean.wall_s > 0 ? clean.sim_s / clean.wall_s : 0.0);
      print_map_honesty("clean", clean);
      std::printf("clean: the motion check learnt the wheels' scale %.5f, spreads along %.5f across %.5f; its largest distance %.2f (chi-square, 1 dof)\n\n",
                  num(est, "motion_scale"), num(est, "motion_spread_along"), num(est, "motion_spread_across"), num(est, "motion_max_d2"));
      // Healthy GNSS refused or overruled by the map: the map was wrong past the gate (a false
      // alarm that, in a race, throws good fixes away).
      if (num(est, "fixes_refused_by_map") > 0 || num(est, "map_overrulings") > 0) {
        std::printf("FAIL: the map refused or overruled healthy GNSS in the clean run (first refusal at %.2f s, first overrule at %.2f s)\n\n",
                    num(est, "map_first_refusal_s"), num(est, "map_first_overrule_s"));
        all_ok = false;
      }
      std::fflush(stdout);
      if (!clean.ok || laps.size() < 3) {
        all_ok = false;
        continue;
      }
      std::printf("| fault | duration | clean runs | contacts | violations | least clearance | slowest lap / clean | error p99 / max | bias found | WARNING / EMERGENCY | WALL / SAFE_STOP | |\n");
      std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
      for (const auto& cls : o.classes)
        for (const auto& d : o.durations) all_ok = fault_row(o, by, graph, tag, base, clean, cls, d) && all_ok;
    }
  }
  return all_ok ? 0 : 1;
}
