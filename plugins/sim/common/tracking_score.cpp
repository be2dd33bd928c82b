#include "tracking_score.hpp"

#include <cmath>
#include <limits>

namespace brickyard::sim {

namespace {
constexpr double kHistoryS = 5.0;  // truth kept: a frame is scored within this of its stamp

double wrap_angle(double a) { return std::remainder(a, 2 * M_PI); }
}  // namespace

std::string TrackingScore::Band::name() const {
  return std::to_string(static_cast<int>(from)) + "_" + std::to_string(static_cast<int>(to));
}

TrackingScore::TrackingScore(TrackingScoreParams p, std::size_t cars) : p_(std::move(p)), others_(cars) {
  double from = 0;
  for (double to : p_.bands) {
    bands_.push_back(Band{from, to, {}, {}, {}, 0});
    from = to;
  }
}

void TrackingScore::keep(std::deque<CarTruth>& h, const CarTruth& s) {
  if (!h.empty() && s.t <= h.back().t) return;  // a sample again
  h.push_back(s);
  while (h.front().t < s.t - kHistoryS) h.pop_front();
}

// Between the samples around t, linearly (the heading the short way round); none outside them.
std::optional<CarTruth> TrackingScore::at(const std::deque<CarTruth>& h, double t) {
  if (h.empty() || t < h.front().t || t > h.back().t) return std::nullopt;
  std::size_t i = 1;
  while (i < h.size() && h[i].t < t) ++i;
  if (i == h.size()) return h.back();
  const CarTruth &a = h[i - 1], &b = h[i];
  const double u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 0.0;
  return CarTruth{t, a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.yaw + u * wrap_angle(b.yaw - a.yaw),
                  a.speed + u * (b.speed - a.speed)};
}

bool TrackingScore::frame(double t, const std::vector<ScoredTrack>& tracks) {
  const auto us = at(ours_, t);
  if (!us) return false;
  const auto est = at(estimate_, t);
  ++frames_;
  std::vector<bool> matched(tracks.size(), false);
  for (const auto& history : others_) {
    const auto car = at(history, t);
    if (!car) continue;
    const double cx = car->x + p_.centre_ahead * std::cos(car->yaw), cy = car->y + p_.centre_ahead * std::sin(car->yaw);
    const double range = std::hypot(cx - us->x, cy - us->y);
    double best = p_.match_radius;
    int nearest = -1;
    for (std::size_t k = 0; k < tracks.size(); ++k) {
      const double e = std::hypot(tracks[k].x - cx, tracks[k].y - cy);
      if (e <= best) {
        best = e;
        nearest = static_cast<int>(k);
      }
    }
    if (nearest >= 0) matched[nearest] = true;
    for (Band& b : bands_) {
      if (range < b.from || range >= b.to) continue;
      if (nearest < 0) {
        ++b.missed;
        continue;
      }
      b.position_errors.push_back(best);
      b.speed_errors.push_back(std::abs(tracks[nearest].speed - car->speed));
      if (est) {  // relative to the estimate, put back by the truth
        const double dx = tracks[nearest].x - est->x, dy = tracks[nearest].y - est->y, turn = us->yaw - est->yaw;
        const double rx = std::cos(turn) * dx - std::sin(turn) * dy, ry = std::sin(turn) * dx + std::cos(turn) * dy;
        b.relative_errors.push_back(std::hypot(us->x + rx - cx, us->y + ry - cy));
      }
    }
  }
  for (std::size_t k = 0; k < tracks.size(); ++k)
    if (!matched[k] && tracks[k].speed > p_.moving_speed) ++phantoms_;
  return true;
}

}  // namespace brickyard::sim
