// sim.localization_scorer: scores one estimator's LocalizationEstimate against the ground truth
// around the fault windows of the run (common/localization_score). Used by the localization
// evaluation (bench/eval_localization) and its graph tests; `require_*` params turn the
// issue's outcomes into a failed run.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/plugin.hpp>

#include "sim/common/localization_samples.hpp"
#include "sim/common/localization_score.hpp"
#include "sim/run_time.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// Reads `[[start_s, end_s], ...]`; throws BadInput naming the parameter and the element.
std::vector<std::pair<double, double>> parse_windows(const std::string& text) {
  const auto w = nlohmann::json::parse(text, nullptr, false);
  if (!w.is_array()) throw BadInput("parameter 'windows': expected an array of [start_s, end_s]");
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& e = w[i];
    if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number() || e[0].get<double>() > e[1].get<double>())
      throw BadInput("parameter 'windows' /" + std::to_string(i) + ": expected [start_s, end_s] with start <= end");
    out.emplace_back(e[0].get<double>(), e[1].get<double>());
  }
  return out;
}

struct Settings {
  ScoreParams score;
  double require_max_error_m = -1, require_emergency_within_s = -1, require_normal_error_below_m = -1;
  bool located_only = false;
  std::string samples_file;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_with(ParamSpec::json("windows", "[]").doc("fault windows [[start_s, end_s], ...]"),
              [](const Params& p, Settings& s) { s.score.windows = parse_windows(p.json("windows")); });
  b.bind("warmup_s", &Settings::score, &ScoreParams::warmup_s).in_unit("s").range(0, 1e7).doc("nothing counts before this");
  b.bind("grace_s", &Settings::score, &ScoreParams::grace_s).in_unit("s").range(0, 3600)
      .doc("after a window: recovery, not a false alarm");
  b.bind("sure_sigma_m", &Settings::score, &ScoreParams::sure_sigma_m).in_unit("m").range(0, 1000)
      .doc("an estimate whose covariance says this or less in every direction (1 sigma) is sure: max_error_sure_m is the largest error of those");
  b.bind("located_only", &Settings::located_only)
      .doc("estimates with update_case 0 are not scored (mapping.map_localizer's frames not located: the guess sent on)");
  b.bind("samples_file", &Settings::samples_file)
      .doc("CSV of every scored estimate beside its truth (localization_samples.hpp); empty: none");
  b.bind("require_max_error_m", &Settings::require_max_error_m).in_unit("m").range(-1000, 1000)
      .doc("fail the run above this max error; < 0: off");
  b.bind("require_emergency_within_s", &Settings::require_emergency_within_s).in_unit("s").range(-3600, 3600)
      .doc("fail unless EMERGENCY within this of the first window; < 0: off");
  b.bind("require_normal_error_below_m", &Settings::require_normal_error_below_m).in_unit("m").range(-1000, 1000)
      .doc("fail if NORMAL while the error exceeds this; < 0: off");
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Input<msgs::LocalizationEstimate> estimate;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(4096);
  b.input("estimate", &Ports::estimate).doc("the estimate to score").depth(4096).steps();
  return b;
}

class Scorer : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.localization_scorer", "1.0.0")
        .describe("scores a localization estimate against ground truth around fault windows")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    score_.emplace(s.score);
    max_error_ = s.require_max_error_m;
    emergency_within_ = s.require_emergency_within_s;
    normal_below_ = s.require_normal_error_below_m;
    located_only_ = s.located_only;
    try {
      if (!s.samples_file.empty()) samples_.emplace(s.samples_file);
    } catch (const std::runtime_error& e) { throw BadInput(std::string("parameter 'samples_file': ") + e.what()); }
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override { drain(ctx); }

  void deactivate(Context& ctx) override {
    drain(ctx);
    const auto& s = *score_;
    for (const auto& [name, value] : score_metrics(s)) ctx.metric(name, value);
    if (samples_) samples_->finish();
    char b[200];
    if (max_error_ >= 0 && s.max_error() > max_error_) {
      std::snprintf(b, sizeof b, "max error %.3f m exceeds the required %.3f m", s.max_error(), max_error_);
      ctx.fail(b);
    }
    if (emergency_within_ >= 0 && (s.time_to_emergency() < 0 || s.time_to_emergency() > emergency_within_)) {
      std::snprintf(b, sizeof b, "EMERGENCY %s (required within %.2f s of the first window)",
                    s.time_to_emergency() < 0 ? "never raised" : ("after " + std::to_string(s.time_to_emergency()) + " s").c_str(),
                    emergency_within_);
      ctx.fail(b);
    }
    if (normal_below_ >= 0 && s.max_error_normal() > normal_below_) {
      std::snprintf(b, sizeof b, "status NORMAL with an error of %.3f m (required below %.3f m)", s.max_error_normal(), normal_below_);
      ctx.fail(b);
    }
    if (s.samples() == 0) ctx.fail("no estimate was scored");
  }

 private:
  void drain(const Context& ctx) {
    for (const auto& s : io_.truth.take()) score_->truth(run_.of(ctx, s->header().stamp_ns()), s->x(), s->y());
    for (const auto& e : io_.estimate.take()) {
      if (located_only_ && e->update_case() == 0) continue;
      const auto& c = e->covariance();
      const PlanarSpread spread{c[0], c[1], c[4]};
      const double t = run_.of(ctx, e->header().stamp_ns());
      if (score_->estimate(t, e->x(), e->y(), e->status(), &spread) && samples_) {
        const auto [tx, ty] = score_->last_truth();
        samples_->add({t, e->x(), e->y(), e->yaw(), c[0], c[1], c[4], c[8], e->status(), e->update_case(), tx, ty});
      }
    }
  }

  std::optional<LocalizationScore> score_;
  std::optional<SampleLog> samples_;
  double max_error_ = -1, emergency_within_ = -1, normal_below_ = -1;
  bool located_only_ = false;
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(Scorer)
