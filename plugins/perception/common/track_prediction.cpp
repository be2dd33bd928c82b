#include "perception/common/track_prediction.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

std::vector<PredictedPoint> predict_along_track(const Track& car, const track::Track& track, const PredictionParams& p) {
  std::vector<PredictedPoint> out;
  const int n = static_cast<int>(std::floor(p.horizon_s / p.step_s + 1e-9));
  double s = car.state[0], d = car.state[1], v = std::max(0.0, car.state[2]), dd = car.state[3], a = car.state[4];
  const double dt = p.step_s;
  // The spread carried as the maneuvering model would: the car may brake or move over at any time.
  Track::Mat F, Q, P = car.cov;
  maneuver_model(dt, p.jerk_sigma, p.lateral_sigma, F, Q);
  for (int k = 1; k <= n; ++k) {
    // Its acceleration and lateral rate fade; its speed stops at 0 (a car braking to a stand).
    const double a_mid = a * std::exp(-0.5 * dt / p.accel_fade_s);
    const double v_next = std::max(0.0, v + a_mid * dt);
    s += (v + v_next) / 2 * dt;
    v = v_next;
    a *= std::exp(-dt / p.accel_fade_s);
    d += dd * p.lateral_fade_s * (1 - std::exp(-dt / p.lateral_fade_s));
    dd *= std::exp(-dt / p.lateral_fade_s);
    // On the road: a car does not leave it to pass (the edge where the map says it is).
    const track::Frenet f = track.at(track.wrap_s(s), d);
    d = std::clamp(d, -track.width_right(f.seg, f.u), track.width_left(f.seg, f.u));
    P = F * P * F.transpose() + Q;
    PredictedPoint pt;
    pt.t = k * dt;
    pt.s = track.wrap_s(s);
    pt.d = d;
    const Eigen::Vector2d xy = track.position(track.at(pt.s, d));
    pt.x = xy.x(), pt.y = xy.y();
    pt.speed = v;
    pt.sigma_s = std::sqrt(P(0, 0));
    pt.sigma_d = std::sqrt(P(1, 1));
    out.push_back(pt);
  }
  return out;
}

}  // namespace brickyard::perception
