#pragma once
// mapping.map_localizer's work over a drive, framework-free: the pose estimates (each frame's
// guess, at its stamp), each frame located on the prior map (MapLocalizer) with the height, roll
// and pitch the last located frame found (the estimate is planar), and the summary's statistics.
// The plugin converts the messages and publishes.
#include "map_localizer.hpp"
#include "mapping_run.hpp"

#include "math/estimate_history.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::mapping {

struct MapLocalizationRunParams {
  MapLocalizerParams localizer;
  double max_estimate_age = 0.1;  // s: a frame with no estimate this near its stamp is left out
  // s: a frame within this of the last one located (or tried) is left out, counted (0: every
  // frame). The cost of the localizer is per frame; the fusion needs a pose only every so often.
  double min_interval_s = 0;
  // s: the same while the estimate is NORMAL (its GNSS taken): the map is then a witness, and a
  // witness needs a fresh pose, not every frame's. The frame after the estimate leaves NORMAL is
  // located: through an outage the fusion steers on every frame (at ten a second, IMS's outer
  // wall alone, all of laps 2 and 3: p99 0.32 m against 0.27 m at twenty). Not sparser: at one
  // frame in 0.2 s both receivers drifting together on Hockenheim's outer wall were caught 5.7 s
  // in, the car 3 m off and 4 s on the wall follower; at 0.1 s, 4.6 s in and 1.3 m, as at 0
  // (frames thinned at 0.8 m then: docs/map-localization.md).
  double normal_interval_s = 0.1;
};

class MapLocalizationRun {
 public:
  MapLocalizationRun(const Points& map, const MapLocalizationRunParams& p);

  void estimate(std::int64_t stamp_ns, const math::PlanarPose& pose, const EstimateExtras& extras);
  // One frame (vehicle frame) located from the estimate at its stamp (interpolated). None,
  // counted, within min_interval_s (normal_interval_s) of the last one tried, or without an estimate within
  // max_estimate_age or with one that is not finite; else the
  // pose (update_case 2: located on the map, 0: not, the guess with the estimate's spreads).
  std::optional<FramePose> frame(std::int64_t stamp_ns, const Points& points);
  // A cloud that could not be read: counted; true for the first (said once).
  bool malformed() { return malformed_++ == 0; }

  const MapLocalizer& localizer() const { return localizer_; }
  // The summary's numbers, in the order they are reported.
  std::vector<std::pair<std::string, double>> metrics() const;

 private:
  FramePose pose_of(std::int64_t stamp, const Located& r, const EstimateExtras& est, const Eigen::Matrix3d& guess_cov) const;

  MapLocalizer localizer_;
  std::int64_t max_age_ns_ = 0, min_interval_ns_ = 0, normal_interval_ns_ = 0, last_tried_ns_ = 0;
  math::EstimateHistory<EstimateExtras> estimates_{256};
  double roll_ = 0, pitch_ = 0, z_ = 0;  // the last located frame's
  std::uint64_t frames_ = 0, located_ = 0, unseen_frames_ = 0, no_estimate_ = 0, malformed_ = 0, skipped_ = 0;
  bool tried_ = false;
  std::uint64_t failures_[static_cast<int>(LocateFailure::singular) + 1] = {};  // per LocateFailure
  double correction_sum_ = 0, correction_max_ = 0;
};

}  // namespace brickyard::mapping
