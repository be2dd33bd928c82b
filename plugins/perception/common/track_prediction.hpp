#pragma once
// Where a tracked car will be (issue 46, docs/tracking.md): its path along the track over the
// planning horizon, with the spread of where it may be. In the track's frame a car holds its line
// and its pace: s moves at the track's speed, its acceleration (braking, powering out) fading over
// `accel_fade_s` (a car does not brake for ever) and never below a stop; d moves at its rate,
// fading over `lateral_fade_s` (a change of line ends on the new line), kept on the road. The
// spread is the track's covariance carried by the maneuvering model (white jerk along, white
// acceleration across): the car may brake or move over at any time within it. Framework-free.
#include "perception/common/object_tracker.hpp"

#include <vector>

namespace brickyard::perception {

struct PredictionParams {
  double horizon_s = 3.0;       // s ahead
  double step_s = 0.1;          // s between points
  double accel_fade_s = 1.0;    // s: its acceleration's time constant
  double lateral_fade_s = 1.0;  // s: its lateral rate's
  double jerk_sigma = 5.0;      // m/s^3: the spread's white jerk along the track
  double lateral_sigma = 2.0;   // m/s^2: its white acceleration across
};

struct PredictedPoint {
  double t = 0;                 // s from the track's time
  double s = 0, d = 0;          // on the track (s wrapped)
  double x = 0, y = 0;          // map frame
  double speed = 0;             // m/s along the track
  double sigma_s = 0, sigma_d = 0;
};

std::vector<PredictedPoint> predict_along_track(const Track& car, const track::Track& track, const PredictionParams& p = {});

}  // namespace brickyard::perception
