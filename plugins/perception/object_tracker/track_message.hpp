#pragma once
// A track, and its path foreseen along the track, as the wire's TrackedObject (the tracker
// plugin's, plugin.cpp).
#include <brickyard/msgs/TrackedObjectList.h>

#include "perception/common/object_tracker.hpp"
#include "perception/common/track_prediction.hpp"

#include <cmath>
#include <cstdint>

namespace brickyard::perception {

inline msgs::TrackedObject track_message(const Track& t, const track::Track& track, const PredictionParams& prediction) {
  msgs::TrackedObject m;
  m.id(t.id);
  m.x(t.xy.x()), m.y(t.xy.y()), m.vx(t.velocity.x()), m.vy(t.velocity.y());
  m.speed(t.speed()), m.heading(t.heading());
  m.s(t.state[0]), m.d(t.state[1]), m.ds(t.state[2]), m.dd(t.state[3]), m.accel(t.state[4]);
  m.speed_sigma(std::sqrt(t.cov(2, 2)));
  m.covariance({t.xy_cov(0, 0), t.xy_cov(0, 1), t.xy_cov(1, 0), t.xy_cov(1, 1)});
  m.size_x(t.size_x), m.size_y(t.size_y);
  m.hits(static_cast<std::uint32_t>(t.hits)), m.age(static_cast<std::uint32_t>(t.age)), m.misses(static_cast<std::uint32_t>(t.misses));
  m.confirmed(t.confirmed);
  if (prediction.horizon_s > 0)
    for (const PredictedPoint& q : predict_along_track(t, track, prediction)) {
      msgs::PredictedPoint p;
      p.t(q.t), p.s(q.s), p.d(q.d), p.x(q.x), p.y(q.y), p.speed(q.speed), p.sigma_s(q.sigma_s), p.sigma_d(q.sigma_d);
      m.prediction().push_back(std::move(p));
    }
  return m;
}

}  // namespace brickyard::perception
