// sim.localization_scorer: scores one estimator's LocalizationEstimate against the ground truth
// around the fault windows of the run (common/localization_score). Used by the localization
// evaluation (bench/eval_localization) and its graph tests; `require_*` params turn the
// issue's outcomes into a failed run.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/plugin.hpp>

#include "../common/localization_score.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

class Scorer : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.localization_scorer", "1.0.0")
        .describe("scores a localization estimate against ground truth around fault windows")
        .input<msgs::VehicleState>("truth", "ground truth", true, 4096)
        .input<msgs::LocalizationEstimate>("estimate", "the estimate to score", true, 4096)
        .param(ParamSpec::json("windows", "[]").doc("fault windows [[start_s, end_s], ...]"))
        .param(ParamSpec::number("warmup_s", 5).in_unit("s").at_least(0).doc("nothing counts before this"))
        .param(ParamSpec::number("grace_s", 2).in_unit("s").at_least(0).doc("after a window: recovery, not a false alarm"))
        .param(ParamSpec::number("require_max_error_m", -1).in_unit("m").doc("fail the run above this max error; < 0: off"))
        .param(ParamSpec::number("require_emergency_within_s", -1).in_unit("s").doc("fail unless EMERGENCY within this of the first window; < 0: off"))
        .param(ParamSpec::number("require_normal_error_below_m", -1).in_unit("m").doc("fail if NORMAL while the error exceeds this; < 0: off"))
        .on_input("estimate");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    ScoreParams sp;
    const auto w = nlohmann::json::parse(p.json("windows"), nullptr, false);
    if (!w.is_array()) throw BadInput("parameter 'windows': expected an array of [start_s, end_s]");
    for (std::size_t i = 0; i < w.size(); ++i) {
      const auto& e = w[i];
      if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number() || e[0].get<double>() > e[1].get<double>())
        throw BadInput("parameter 'windows' /" + std::to_string(i) + ": expected [start_s, end_s] with start <= end");
      sp.windows.emplace_back(e[0].get<double>(), e[1].get<double>());
    }
    sp.warmup_s = p.number("warmup_s");
    sp.grace_s = p.number("grace_s");
    score_.emplace(sp);
    max_error_ = p.number("require_max_error_m");
    emergency_within_ = p.number("require_emergency_within_s");
    normal_below_ = p.number("require_normal_error_below_m");
    truth_ = ctx.input<msgs::VehicleState>("truth");
    est_ = ctx.input<msgs::LocalizationEstimate>("estimate");
  }

  void step(Context&) override { drain(); }

  void deactivate(Context& ctx) override {
    drain();
    const auto& s = *score_;
    ctx.metric("samples", static_cast<double>(s.samples()));
    ctx.metric("rmse_m", s.rmse());
    ctx.metric("max_error_m", s.max_error());
    ctx.metric("max_error_normal_m", s.max_error_normal());
    ctx.metric("time_to_flag_s", s.time_to_flag());
    ctx.metric("time_to_emergency_s", s.time_to_emergency());
    ctx.metric("false_alarms", static_cast<double>(s.false_alarms()));
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
  void drain() {
    for (const auto& s : truth_.take()) score_->truth(static_cast<double>(s->header().stamp_ns()) * 1e-9, s->x(), s->y());
    for (const auto& e : est_.take()) score_->estimate(static_cast<double>(e->header().stamp_ns()) * 1e-9, e->x(), e->y(), e->status());
  }

  std::optional<LocalizationScore> score_;
  double max_error_ = -1, emergency_within_ = -1, normal_below_ = -1;
  Input<msgs::VehicleState> truth_;
  Input<msgs::LocalizationEstimate> est_;
};

}  // namespace

BRICKYARD_PLUGINS(Scorer)
