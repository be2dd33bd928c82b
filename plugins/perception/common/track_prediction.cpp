#include "perception/common/track_prediction.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

namespace {

// The track's covariance over (s, d, ds/dt, dd/dt, d2s/dt2) carried dt on, as the maneuvering
// model would (constant acceleration along, white jerk; constant velocity across, white acceleration).
Track::Mat carried(const Track::Mat& P, double dt, const PredictionParams& p) {
  Track::Mat F = Track::Mat::Identity();
  F(0, 2) = F(1, 3) = F(2, 4) = dt;
  F(0, 4) = dt * dt / 2;
  const double t2 = dt * dt, t3 = t2 * dt, t4 = t3 * dt, t5 = t4 * dt;
  const double j = p.jerk_sigma * p.jerk_sigma, a = p.lateral_sigma * p.lateral_sigma;
  const int along[3] = {0, 2, 4};
  const double G[3][3] = {{t5 / 20, t4 / 8, t3 / 6}, {t4 / 8, t3 / 3, t2 / 2}, {t3 / 6, t2 / 2, dt}};
  Track::Mat Q = Track::Mat::Zero();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Q(along[r], along[c]) = j * G[r][c];
  Q(1, 1) = a * t4 / 4, Q(1, 3) = Q(3, 1) = a * t3 / 2, Q(3, 3) = a * t2;
  return F * P * F.transpose() + Q;
}

}  // namespace

std::vector<PredictedPoint> predict_along_track(const Track& car, const track::Track& track, const PredictionParams& p) {
  std::vector<PredictedPoint> out;
  const int n = static_cast<int>(std::floor(p.horizon_s / p.step_s + 1e-9));
  double s = car.state[0], d = car.state[1], v = std::max(0.0, car.state[2]), dd = car.state[3], a = car.state[4];
  Track::Mat P = car.cov;
  for (int k = 1; k <= n; ++k) {
    const double dt = p.step_s;
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
    P = carried(P, dt, p);
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
