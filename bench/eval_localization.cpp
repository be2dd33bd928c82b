// The localization evaluation of eight GNSS fault scenarios on IMS, the car driven on
// ground truth, the three estimators side by side on the same sensor data
// (configs/eval/localization.json), each scored by sim.localization_scorer. Prints the table of
// docs/results-localization.md and checks the issue's required outcomes (exit 1 if one fails).
// usage: eval_localization [--seed N]
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace {

struct Scenario {
  const char* name;
  const char* left;   // faults of gnss_left (receiver 0), JSON
  const char* right;  // faults of gnss_right (receiver 1)
  double start, end;  // the fault window, s
  bool single;        // one receiver only
};

// Faults from t = 20 s; each run lasts 25 s past its window. The double degradation is the
// paper's t = 498-505 s event, 7 s long, moved to t = 20 s: both receivers 15 m off (the metres
// of a lost fix) with 0.45 m noise.
const Scenario kScenarios[] = {
    {"clean", "[]", "[]", 20, 20, false},
    {"step 0.4 m, one receiver, 20 s", R"([{"type":"bias","start_s":20,"end_s":40,"offset":[0.4,0,0]}])", "[]", 20, 40, true},
    {"jump 3 m, one receiver", R"([{"type":"bias","start_s":20,"end_s":30,"offset":[0,3,0]}])", "[]", 20, 30, true},
    {"both degraded 7 s", R"([{"type":"bias","start_s":20,"end_s":27,"offset":[12,-9,0]},{"type":"noise","start_s":20,"end_s":27,"factor":30}])",
     R"([{"type":"bias","start_s":20,"end_s":27,"offset":[-10,11,0]},{"type":"noise","start_s":20,"end_s":27,"factor":30}])", 20, 27, false},
    {"drift 0.5 m/s, one receiver", R"([{"type":"drift","start_s":20,"end_s":40,"rate":[0.5,0,0]}])", "[]", 20, 40, true},
    {"both drop out 3 s", R"([{"type":"dropout","start_s":20,"end_s":23}])", R"([{"type":"dropout","start_s":20,"end_s":23}])", 20, 23, false},
    {"spikes, one receiver", R"([{"type":"spikes","start_s":20,"end_s":30,"probability":0.2,"magnitude":8}])", "[]", 20, 30, true},
    {"sigma misreported, one receiver", R"([{"type":"noise","start_s":20,"end_s":30,"factor":25},{"type":"sigma","start_s":20,"end_s":30,"factor":0.5}])", "[]", 20, 30, true},
};
// 5 mm: a third of the receivers' 1.5 cm sigma; max errors closer than that are a tie.
constexpr double kTie = 0.005;
const char* kEstimators[] = {"resilient", "naive", "gated", "resilient_paper"};

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

int main(int argc, char** argv) {
  int seed = 1;
  if (argc > 2 && std::strcmp(argv[1], "--seed") == 0) seed = std::atoi(argv[2]);
  const std::string src = BRICKYARD_SOURCE_DIR, by = BRICKYARD_HOST;
  std::printf("| scenario | estimator | RMSE (m) | max error (m) | max error while NORMAL (m) | time to flag (s) | time to EMERGENCY (s) | false alarms |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> failures, ties;
  for (const auto& sc : kScenarios) {
    const double duration = sc.end + 25;
    const std::string windows = sc.end > sc.start ? "[[" + std::to_string(sc.start) + "," + std::to_string(sc.end) + "]]" : "[]";
    std::string cmd = by + " run " + src + "/configs/eval/localization.json --quiet --seed " + std::to_string(seed) +
                      " --duration " + std::to_string(duration) + " --out /tmp/eval_localization" +
                      " --set " + quote(std::string("gnss_left.faults=") + sc.left) + " --set " +
                      quote(std::string("gnss_right.faults=") + sc.right);
    for (const char* e : kEstimators) cmd += " --set " + quote(std::string("score_") + e + ".windows=" + windows);
    cmd += " > /tmp/eval_localization.log 2>&1";
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "run failed: %s (see /tmp/eval_localization.log)\n", cmd.c_str());
      return 1;
    }
    std::ifstream f("/tmp/eval_localization/summary.json");
    const auto j = nlohmann::json::parse(f);
    double max_err[4];
    for (int i = 0; i < 4; ++i) {
      const auto& m = j["nodes"][std::string("score_") + kEstimators[i]]["metrics"];
      auto num = [&](const char* k) { return m[k].is_number() ? m[k].get<double>() : NAN; };
      auto when = [&](const char* k) {
        char b[32];
        if (num(k) < 0) return std::string("—");
        std::snprintf(b, sizeof b, "%.3f", num(k));
        return std::string(b);
      };
      max_err[i] = num("max_error_m");
      std::printf("| %s | %s | %.3f | %.3f | %.3f | %s | %s | %.0f |\n", sc.name, kEstimators[i], num("rmse_m"), max_err[i],
                  num("max_error_normal_m"), when("time_to_flag_s").c_str(), when("time_to_emergency_s").c_str(),
                  num("false_alarms"));
      if (i == 0) {
        if (num("max_error_normal_m") > 1.0) failures.push_back(std::string(sc.name) + ": resilient NORMAL with an error above 1 m");
        if (sc.single && max_err[0] > 0.5) failures.push_back(std::string(sc.name) + ": resilient max error above 0.5 m");
        if (std::strncmp(sc.name, "both degraded", 13) == 0 && !(num("time_to_emergency_s") >= 0 && num("time_to_emergency_s") <= 0.5))
          failures.push_back(std::string(sc.name) + ": EMERGENCY not within 0.5 s");
      }
    }
    // Lowest of the three; within kTie of the lowest counts as a tie at the floor all share.
    if (sc.end > sc.start && !(max_err[0] <= max_err[1] + kTie && max_err[0] <= max_err[2] + kTie))
      failures.push_back(std::string(sc.name) + ": resilient does not have the lowest max error");
    if (sc.end > sc.start && !(max_err[0] < max_err[1] && max_err[0] < max_err[2]))
      ties.push_back(sc.name);
  }
  std::printf("\n");
  for (const auto& t : ties) std::printf("tie (within %.0f mm, not strictly lowest): %s\n", kTie * 1e3, t.c_str());
  for (const auto& f : failures) std::printf("NOT MET: %s\n", f.c_str());
  if (failures.empty()) std::printf("all required outcomes met\n");
  return failures.empty() ? 0 : 1;
}
