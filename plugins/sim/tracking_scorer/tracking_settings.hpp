#pragma once
// sim.tracking_scorer's parameters: how tracks are matched and banded, and what fails the run.
#include <brickyard/plugin.hpp>

#include "sim/common/tracking_score.hpp"

namespace brickyard::sim {

struct TrackingScorerSettings {
  TrackingScoreParams score;
  double require_position_error_m = -1, require_speed_error_mps = -1;  // p95 in the band around 50 m
  std::int64_t require_max_phantoms = -1;
};

inline ParamBinding<TrackingScorerSettings> tracking_scorer_bindings() {
  using P = TrackingScoreParams;
  ParamBinding<TrackingScorerSettings> b;
  b.bind("match_radius_m", &TrackingScorerSettings::score, &P::match_radius).in_unit("m").range(0.1, 100)
      .doc("a track this near a car's centre is that car's");
  b.bind("bands_m", &TrackingScorerSettings::score, &P::bands).in_unit("m").range(1, 10000).doc("the range bands' far ends, rising");
  b.bind("moving_speed", &TrackingScorerSettings::score, &P::moving_speed).in_unit("m/s").range(0, 100)
      .doc("a track this fast near no car is a phantom");
  b.bind("centre_ahead", &TrackingScorerSettings::score, &P::centre_ahead).in_unit("m").range(-10, 10)
      .doc("a car's footprint centre ahead of its base_link (the AV-21's: (3.9 - 1.0) / 2)");
  b.bind("require_position_error_m", &TrackingScorerSettings::require_position_error_m).in_unit("m").range(-1, 100)
      .doc("fail above this p95 position error in the band holding 50 m; < 0: off");
  b.bind("require_speed_error_mps", &TrackingScorerSettings::require_speed_error_mps).in_unit("m/s").range(-1, 100)
      .doc("fail above this p95 speed error in the band holding 50 m; < 0: off");
  b.bind("require_max_phantoms", &TrackingScorerSettings::require_max_phantoms).range(-1, 1e9).doc("fail above this many phantom tracks; < 0: off");
  return b;
}

}  // namespace brickyard::sim
