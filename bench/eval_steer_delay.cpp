// How late may the steering be? tests/graphs/car_direct.json (the car stack on its GNSS, IMU
// and wheels, the LQR tracker; the simulator in the same process, sim clock) two laps on every
// track in a folder, the simulated car's steering delay swept while the tracker keeps planning
// with the vehicle file's 20 ms and its own `command_latency`: as a command's way through a bus,
// a manager and a loaded host lengthens it on the car (docs/car-on-wires.md). Each run twice:
// the tracker's defaults, and the baseline of the same law planning over the vehicle file's
// steering delay alone with no cost on the rate (command_latency 0, r_steer_rate 0). Seeds too:
// the sensors' noise. Prints per track and delay: the runs that finished both laps clean, the
// least wall clearance, the worst lap against the delay-free run's, and the steering's rate
// (RMS; an oscillating tracker's grows many times over). docs/control.md.
// usage: eval_steer_delay [--tracks DIR] [--delays D,D,...] [--seeds N] [--jobs N] [--domain N] [--set NODE.PARAM=V]...
// Exit 1 when a run of the tracker's defaults failed (the baseline's failures are the point).
#include "race_runs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using brickyard::bench::RaceRun;

double num(const json& m, const char* k) { return brickyard::bench::metric(m, k); }

struct Job {
  std::string track, law, vehicle_file, dir;
  std::vector<std::string> args, sets;
  double delay = 0;
  int seed = 0;
  RaceRun run;
};

// The vehicle file with its steering delay replaced, written beside the runs.
std::string vehicle_with_delay(const std::string& vehicle, double delay, const std::string& dir) {
  std::ifstream in(vehicle);
  json v = json::parse(in);
  v["steering"]["delay_s"] = delay;
  char name[64];
  std::snprintf(name, sizeof name, "/vehicle_delay_%.3f.json", delay);
  const std::string path = dir + name;
  std::ofstream(path) << v.dump(2);
  return path;
}

std::vector<double> parse_list(const char* s) {
  std::vector<double> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(std::atof(item.c_str()));
  return out;
}

void run_all(std::vector<Job>& jobs, int workers, int domain0, const std::string& by, const std::string& graph) {
  std::atomic<std::size_t> next{0};
  auto worker = [&](int domain) {
    for (std::size_t k; (k = next++) < jobs.size();) {
      Job& j = jobs[k];
      std::vector<std::string> sets = j.sets;
      sets.push_back("car.vehicle=" + j.vehicle_file);
      j.run = brickyard::bench::run_race(by, graph, j.args, sets, j.seed, j.dir, domain);
    }
  };
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(worker, domain0 + w);
  for (auto& t : pool) t.join();
}

bool clean(const RaceRun& r) { return r.ok && num(r.referee, "wall_contacts") == 0 && num(r.referee, "track_violations") == 0; }

// The table, a row per track, delay and law; whether every run of the tracker's defaults was clean.
bool print_table(const std::vector<Job>& jobs, const std::vector<std::string>& names, const std::vector<double>& delays,
                 const std::vector<std::pair<std::string, std::vector<std::string>>>& laws) {
  std::printf("| track | steering delay | tracker | clean runs | least clearance | worst lap vs the delay-free run | steering rate RMS |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  bool defaults_ok = true;
  for (const auto& name : names)
    for (double d : delays)
      for (const auto& law : laws) {
        int ok = 0, n = 0;
        double least = INFINITY, worst_lap = 0, rate = 0;
        std::string why;
        for (const Job& j : jobs) {
          if (j.track != name || j.delay != d || j.law != law.first) continue;
          ++n;
          if (clean(j.run)) ++ok;
          else if (why.empty())
            why = " (seed " + std::to_string(j.seed) + ": " +
                  (j.run.ok ? "finished with " + std::to_string(static_cast<int>(num(j.run.referee, "wall_contacts"))) + " wall contact(s)"
                            : j.run.reason) + ")";
          least = std::min(least, num(j.run.referee, "min_wall_clearance_m"));
          rate = std::max(rate, num(j.run.nodes.value("path_tracker", json::object()), "steer_rate_rms_radps"));
          // Against the same law, seed and track with no delay: what the delay costs in time.
          for (const Job& ref : jobs)
            if (ref.track == name && ref.law == law.first && ref.seed == j.seed && ref.delay == delays.front() && clean(ref.run) && clean(j.run)) {
              const json &a = j.run.referee["lap_times_s"], &b = ref.run.referee["lap_times_s"];
              for (std::size_t l = 0; l < std::min(a.size(), b.size()); ++l)
                worst_lap = std::max(worst_lap, a[l].get<double>() / b[l].get<double>() - 1);
            }
        }
        if (law.first == "defaults" && ok < n) defaults_ok = false;
        std::printf("| %s | %.0f ms | %s | %d of %d%s | %.2f m | %+.2f %% | %.3f rad/s |\n", name.c_str(), 1000 * d, law.first.c_str(), ok,
                    n, why.c_str(), least, 100 * worst_lap, rate);
      }
  return defaults_ok;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string src = BRICKYARD_SOURCE_DIR, by = BRICKYARD_HOST;
  std::string tracks = src + "/data/tracks";
  std::vector<double> delays = {0, 0.02, 0.04, 0.06, 0.08};
  std::vector<std::string> user_sets;
  int seeds = 2, workers = 1, domain0 = 150;
  if (const int rc = brickyard::bench::check_option_pairs(argc, argv, "usage: eval_steer_delay [--tracks DIR] [--delays D,D,...] [--seeds N] [--jobs N] [--domain N] [--set NODE.PARAM=V]..."); rc >= 0) return rc;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--tracks")) tracks = argv[i + 1];
    else if (!std::strcmp(argv[i], "--delays")) delays = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--seeds")) seeds = std::clamp(std::atoi(argv[i + 1]), 1, 100);
    else if (!std::strcmp(argv[i], "--jobs")) workers = std::clamp(std::atoi(argv[i + 1]), 1, 16);
    else if (!std::strcmp(argv[i], "--domain")) domain0 = std::clamp(std::atoi(argv[i + 1]), 0, 200);
    else if (!std::strcmp(argv[i], "--set")) user_sets.push_back(argv[i + 1]);
    else {
      std::fprintf(stderr, "eval_steer_delay: %s: unknown option\n", argv[i]);
      return 2;
    }
  }
  if (delays.empty() || std::any_of(delays.begin(), delays.end(), [](double d) { return !(d >= 0 && d <= 0.25); })) {
    std::fprintf(stderr, "eval_steer_delay: --delays: seconds in [0, 0.25] (a vehicle file's steering delay), comma-separated\n");
    return 2;
  }
  if (!fs::is_directory(tracks)) {
    std::fprintf(stderr, "eval_steer_delay: --tracks %s: not a folder of track files\n", tracks.c_str());
    return 2;
  }
  const std::string dir = std::getenv("EVAL_STEER_DELAY_DIR") ? std::getenv("EVAL_STEER_DELAY_DIR") : "/tmp/eval_steer_delay";
  fs::create_directories(dir);
  const std::string graph = src + "/tests/graphs/car_direct.json", vehicle = src + "/data/vehicles/av21.json";
  const std::vector<std::pair<std::string, std::vector<std::string>>> laws = {
      {"defaults", {}}, {"delay alone", {"path_tracker.command_latency=0", "path_tracker.r_steer_rate=0"}}};
  std::vector<Job> jobs;
  std::vector<std::string> names;
  for (const auto& tf : brickyard::bench::track_files(tracks)) {
    if (!tf.error.empty()) {
      std::fprintf(stderr, "eval_steer_delay: %s\n", tf.error.c_str());
      return 2;
    }
    names.push_back(tf.name);
    const auto args = brickyard::bench::track_args(tf.path, tf.name, tf.line, false);
    for (double d : delays) {
      const std::string file = vehicle_with_delay(vehicle, d, dir);
      for (const auto& [law, law_sets] : laws)
        for (int seed = 0; seed < seeds; ++seed) {
          Job j{tf.name, law, file, {}, args, law_sets, d, seed, {}};
          j.sets.insert(j.sets.end(), user_sets.begin(), user_sets.end());
          char tag[96];
          std::snprintf(tag, sizeof tag, "/%s_%s_%.3f_s%d", tf.name.c_str(), law == "defaults" ? "defaults" : "alone", d, seed);
          j.dir = dir + tag;
          jobs.push_back(std::move(j));
        }
    }
  }
  run_all(jobs, workers, domain0, by, graph);

  const bool defaults_ok = print_table(jobs, names, delays, laws);
  std::printf("%s\n", defaults_ok ? "every run of the tracker's defaults finished clean"
                                   : "FAIL: a run of the tracker's defaults did not finish clean (the table says which)");
  return defaults_ok ? 0 : 1;
}
