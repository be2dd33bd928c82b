#pragma once
// mapping.map_localizer's parameters (plugin.cpp): the map file and the localizer's. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "mapping/common/map_localization_run.hpp"

#include <string>

namespace brickyard::mapping {

struct LocalizerSettings : MapLocalizationRunParams {
  std::string map_file;
  std::string track;         // empty: the map is not checked against a track
  double track_reach = 30;   // m
  double track_share = 0.9;  // of the centre line within track_reach of the map
};

inline ParamBinding<LocalizerSettings> localizer_bindings() {
  using S = LocalizerSettings;
  using M = MapLocalizerParams;
  ParamBinding<S> b;
  b.bind_required("map_file", &S::map_file)
      .doc("the prior map of the track: a PCD file (x y z float, binary or ascii) as mapping.scan_mapper writes it");
  b.bind("track", &S::track)
      .doc("the track the map is of (a centre-line file, as the world's): a map that does not cover it is refused at validation");
  b.bind("track_reach", &S::track_reach).in_unit("m").range(1, 1000).doc("a centre-line point this near a map point is covered");
  b.bind("track_share", &S::track_share).range(0, 1).doc("the share of the centre line the map must cover");
  b.bind("coarse_voxel", &S::localizer, &M::coarse_voxel).in_unit("m").range(0.05, 10)
      .doc("the map registered on first, from the estimate: reaches far");
  b.bind("fine_voxel", &S::localizer, &M::fine_voxel).in_unit("m").range(0.02, 10).doc("then on this one, accurate near the answer");
  b.bind("scan_voxel", &S::localizer, &M::scan_voxel).in_unit("m").range(0.05, 10)
      .doc("the frame thinned to one point (the mean) per voxel of this size: the localizer's cost goes with the points left");
  b.bind("max_range", &S::localizer, &M::max_range).in_unit("m").range(1, 1000).doc("points farther from the car are left out");
  b.bind("max_correction", &S::localizer, &M::max_correction).in_unit("m").range(0, 100)
      .doc("a pose farther from the estimate is not taken");
  b.bind("max_turn", &S::localizer, &M::max_turn).in_unit("rad").range(0, 3.14).doc("nor one turned more");
  b.bind("min_support", &S::localizer, &M::min_support).range(0, 1e6)
      .doc("a direction with less of the frame's surface facing it (points' worth) is one the map cannot tell");
  b.bind("unseen_sigma", &S::localizer, &M::unseen_sigma).in_unit("m").range(0.1, 1e4)
      .doc("the spread reported along a direction the map cannot tell (the estimate's coordinate kept there)");
  b.bind("ground_tilt", &S::localizer, &M::ground_tilt).in_unit("rad").range(0, 1.5)
      .doc("surfaces within this of level (the road) are made level in the map and the frame: they tell height, roll and pitch, not the plane position (0: kept)");
  b.bind("min_sigma", &S::localizer, &M::min_sigma).in_unit("m").range(0, 100)
      .doc("the least spread reported in any direction of the position: what the map's making adds to the registration's own");
  b.bind("points_worth", &S::localizer, &M::points_worth).range(1, 1e6)
      .doc("how many independent points a frame counts as: the pose's covariance");
  b.bind("threads", &S::localizer, &M::threads).range(1, 2)
      .doc("threads that share the map's preparation at the start (its surfaces, its voxels): the same bits on either");
  b.bind("max_estimate_age", &S::max_estimate_age).in_unit("s").range(0, 60)
      .doc("a frame with no estimate within this of its stamp is left out");
  b.bind("min_interval_s", &S::min_interval_s).in_unit("s").range(0, 10)
      .doc("a frame within this of the last one tried is left out (0: every frame): the localizer's cost is per frame");
  b.bind("normal_interval_s", &S::normal_interval_s).in_unit("s").range(0, 10)
      .doc("the same while the estimate is NORMAL (GNSS taken; the map a witness): at least min_interval_s");
  // The host's (Manifest::delivered_after): the pose found takes the localizer's computing time.
  b.declare(ParamSpec::number("latency_s", 0).in_unit("s").range(0, 0.05)
                .doc("a pose, stamped at its frame, is delivered this long after the frame came (sim clock): the time the "
                     "localizer takes on the car; its step runs beside what follows meanwhile (0: at once)"));
  b.not_above("fine_voxel", "coarse_voxel");
  return b;
}

}  // namespace brickyard::mapping
