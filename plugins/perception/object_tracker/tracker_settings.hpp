#pragma once
// perception.object_tracker's parameters: the tracker's, the prediction's, the other cars' model.
#include <brickyard/plugin.hpp>

#include "perception/common/object_tracker.hpp"
#include "perception/common/track_prediction.hpp"
#include "vehicle_param.hpp"

namespace brickyard::perception {

struct TrackerSettings {
  TrackerParams tracker;
  PredictionParams prediction;
  bool confirmed_only = true;
  std::string vehicle = plugins::default_vehicle_file;  // the other cars' model: their footprint
};

inline ParamBinding<TrackerSettings> tracker_bindings() {
  using T = TrackerParams;
  ParamBinding<TrackerSettings> b;
  b.bind("accel_sigma", &TrackerSettings::tracker, &T::accel_sigma).in_unit("m/s^2").range(0.01, 100).doc("white acceleration along the track");
  b.bind("lateral_accel_sigma", &TrackerSettings::tracker, &T::lateral_accel_sigma).in_unit("m/s^2").range(0.01, 100).doc("white acceleration across it");
  b.bind("jerk_sigma", &TrackerSettings::tracker, &T::jerk_sigma).in_unit("m/s^3").range(0.01, 1000)
      .doc("white jerk along the track: the maneuvering model (braking and powering change at once)");
  b.bind("meas_sigma", &TrackerSettings::tracker, &T::meas_sigma).in_unit("m").range(0.001, 10).doc("a detection's position, 1 sigma");
  b.bind("meas_sigma_per_m", &TrackerSettings::tracker, &T::meas_sigma_per_m).range(0, 1).doc("m of spread added per m of range");
  b.bind("gate", &TrackerSettings::tracker, &T::gate).range(0.1, 1000).doc("chi-square (2 dof) within which a detection may be a track's");
  b.bind("birth_speed_sigma", &TrackerSettings::tracker, &T::birth_speed_sigma).in_unit("m/s").range(0.1, 200).doc("a new track's velocity spread");
  b.bind("confirm_hits", &TrackerSettings::tracker, &T::confirm_hits).range(1, 30).doc("hits that confirm a track ...");
  b.bind("confirm_window", &TrackerSettings::tracker, &T::confirm_window).range(1, 30).doc("... within its first this many frames");
  b.bind("max_misses", &TrackerSettings::tracker, &T::max_misses).range(0, 1000).doc("frames a confirmed track may go unseen");
  b.bind("max_sigma", &TrackerSettings::tracker, &T::max_sigma).in_unit("m").range(0.01, 1000).doc("a track more spread than this is dropped");
  b.bind("confirmed_only", &TrackerSettings::confirmed_only).doc("publish only confirmed tracks");
  b.bind("horizon_s", &TrackerSettings::prediction, &PredictionParams::horizon_s).in_unit("s").range(0, 30).doc("each track's path foreseen this far (0: none)");
  b.bind("prediction_step_s", &TrackerSettings::prediction, &PredictionParams::step_s).in_unit("s").range(0.01, 5).doc("between its points");
  plugins::bind_vehicle(b, &TrackerSettings::vehicle).doc("the other cars' model (data/vehicles/): their length and width");
  b.bind("whole_cars", &TrackerSettings::tracker, &T::whole_cars).doc("a car's parts merged and completed to its footprint's centre");
  b.bind("car_min_extent", &TrackerSettings::tracker, &T::car, &CarShape::min_extent).in_unit("m").range(0, 100)
      .doc("a detection this long or wide is (part of) a car");
  b.bind("car_join_gap", &TrackerSettings::tracker, &T::car, &CarShape::join_gap).in_unit("m").range(0, 100)
      .doc("the parts of one car lie this close to each other");
  b.bind("road_margin", &TrackerSettings::tracker, &T::road_margin).in_unit("m").range(-100, 100)
      .doc("a detection's centre this far inside the road's edges at least, or it is not followed");
  b.not_above("confirm_hits", "confirm_window");
  return b;
}

}  // namespace brickyard::perception
