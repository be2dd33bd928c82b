// sim.tracking_scorer: a tracker's confirmed tracks against the other cars' truth
// (common/tracking_score.hpp): position and speed errors and misses by range band, phantoms.
// `require_*` turn the targets into a failed run.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/TrackedObjectList.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/plugin.hpp>

#include "sim/common/perception_score.hpp"
#include "sim/common/tracking_score.hpp"
#include "sim/tracking_scorer/tracking_settings.hpp"
#include "sim/world_msg.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <cstdio>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::VehicleState> truth;
  Input<msgs::TrackedObjectList> tracks;
  Input<msgs::LocalizationEstimate> estimate;
  std::array<Input<msgs::VehicleState>, kOtherCars> others;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("our car's truth").depth(4096);
  b.input("tracks", &Ports::tracks).doc("a tracker's output").depth(256).steps();
  b.input("estimate", &Ports::estimate).doc("our pose as the stack estimated it (optional): errors placed by the true pose too").optional().depth(4096);
  b.inputs("other", &Ports::others).doc("another car's truth (other0 to other3)").required_first(1).depth(4096);
  return b;
}

CarTruth truth_of(const msgs::VehicleState& s) {
  return {static_cast<double>(stamp(s)) * 1e-9, s.x(), s.y(), s.yaw(), std::hypot(s.vx(), s.vy())};
}

class TrackingScorer : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.tracking_scorer", "1.0.0")
        .describe("scores tracked objects against the other cars' truth: position and speed errors by range, misses, phantoms")
        .with_ports(ports())
        .parameters(tracking_scorer_bindings());
  }

  void configure(Context& ctx) override {
    settings_ = tracking_scorer_bindings().read(ctx.params());
    const auto& bands = settings_.score.bands;
    if (bands.empty() || std::adjacent_find(bands.begin(), bands.end(), std::greater_equal<double>()) != bands.end())
      throw BadInput("parameter 'bands_m': the range bands' far ends must rise, one at least");
    score_.emplace(settings_.score, kOtherCars);
    io_ = ports().connect(ctx);
  }

  void step(Context&) override { drain(); }

  void deactivate(Context& ctx) override {
    drain();
    ctx.metric("frames", static_cast<double>(score_->frames()));
    ctx.metric("phantom_tracks", static_cast<double>(score_->phantoms()));
    for (const auto& b : score_->bands()) {
      const std::size_t tracked = b.position_errors.size();
      ctx.metric("tracked_" + b.name(), static_cast<double>(tracked));
      ctx.metric("missed_" + b.name(), static_cast<double>(b.missed));
      if (tracked == 0) continue;
      ctx.metric("position_error_p95_m_" + b.name(), PerceptionScore::percentile(b.position_errors, 0.95));
      ctx.metric("position_error_max_m_" + b.name(), PerceptionScore::percentile(b.position_errors, 1.0));
      if (!b.relative_errors.empty()) {
        ctx.metric("relative_error_p95_m_" + b.name(), PerceptionScore::percentile(b.relative_errors, 0.95));
        ctx.metric("relative_error_max_m_" + b.name(), PerceptionScore::percentile(b.relative_errors, 1.0));
      }
      ctx.metric("speed_error_p95_mps_" + b.name(), PerceptionScore::percentile(b.speed_errors, 0.95));
      ctx.metric("speed_error_max_mps_" + b.name(), PerceptionScore::percentile(b.speed_errors, 1.0));
    }
    require(ctx);
  }

 private:
  void drain() {
    for (const auto& s : io_.truth.take()) score_->ours(truth_of(*s));
    for (const auto& e : io_.estimate.take()) score_->estimate({static_cast<double>(e->header().stamp_ns()) * 1e-9, e->x(), e->y(), e->yaw(), e->speed()});
    for (std::size_t i = 0; i < kOtherCars; ++i)
      for (const auto& s : io_.others[i].take()) score_->other(i, truth_of(*s));
    for (const auto& l : io_.tracks.take()) {
      tracks_.clear();
      for (const auto& o : l->objects()) tracks_.push_back({o.x(), o.y(), o.speed()});
      score_->frame(static_cast<double>(l->header().stamp_ns()) * 1e-9, tracks_);
    }
  }

  void require(Context& ctx) {
    char b[200];
    if (settings_.require_max_phantoms >= 0 && static_cast<std::int64_t>(score_->phantoms()) > settings_.require_max_phantoms) {
      std::snprintf(b, sizeof b, "%zu phantom tracks (at most %lld allowed)", score_->phantoms(),
                    static_cast<long long>(settings_.require_max_phantoms));
      ctx.fail(b);
    }
    for (const auto& band : score_->bands()) {
      if (band.from > 50 || band.to <= 50) continue;
      if (band.position_errors.empty() && (settings_.require_position_error_m >= 0 || settings_.require_speed_error_mps >= 0)) {
        ctx.fail("no car was tracked between " + band.name() + " m: nothing to score");
        continue;
      }
      const double p = PerceptionScore::percentile(band.position_errors, 0.95), v = PerceptionScore::percentile(band.speed_errors, 0.95);
      if (settings_.require_position_error_m >= 0 && p > settings_.require_position_error_m) {
        std::snprintf(b, sizeof b, "position error p95 %.3f m at %s m exceeds the required %.3f m", p, band.name().c_str(),
                      settings_.require_position_error_m);
        ctx.fail(b);
      }
      if (settings_.require_speed_error_mps >= 0 && v > settings_.require_speed_error_mps) {
        std::snprintf(b, sizeof b, "speed error p95 %.3f m/s at %s m exceeds the required %.3f m/s", v, band.name().c_str(),
                      settings_.require_speed_error_mps);
        ctx.fail(b);
      }
    }
  }

  TrackingScorerSettings settings_;
  std::optional<TrackingScore> score_;
  std::vector<ScoredTrack> tracks_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(TrackingScorer)
