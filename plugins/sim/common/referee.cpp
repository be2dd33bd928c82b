#include "referee.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

Referee::Referee(const Track& track, Footprint fp) : track_(track), fp_(fp), pylon_hit_(track.spec().pylons.size()) {}

Referee::Events Referee::update(const TruthSample& s) {
  Events ev;
  const double L = track_.length();
  Frenet f = track_.project(s.x, s.y, hint_);
  hint_ = f.seg;
  if (!started_) {
    started_ = true;
    // A car that starts on the line (within 20 m past it) starts its first lap now.
    if (f.s < 20.0) { timing_ = true; lap_start_ = s.t; }
  } else if (last_s_ > L - 100.0 && f.s < 100.0) {
    // Crossed the start line forwards: the crossing time by linear interpolation.
    double before = L - last_s_, after = f.s;
    double tc = last_t_ + (s.t - last_t_) * before / std::max(before + after, 1e-9);
    if (timing_) {
      lap_times_.push_back(tc - lap_start_);
      ev.lap_completed = true;
    }
    timing_ = true;
    lap_start_ = tc;
  }
  last_s_ = f.s;
  last_t_ = s.t;
  max_speed_ = std::max(max_speed_, s.speed);
  if (s.speed >= 0.5) {
    moved_ = true;
    last_moving_t_ = s.t;
  }

  // Corners of the car against the wall lines.
  const double c = std::cos(s.yaw), sn = std::sin(s.yaw);
  const double corners[4][2] = {{fp_.front, fp_.half_width}, {fp_.front, -fp_.half_width},
                                {-fp_.rear, fp_.half_width}, {-fp_.rear, -fp_.half_width}};
  double clearance = std::numeric_limits<double>::infinity();
  for (const auto& k : corners) {
    double x = s.x + c * k[0] - sn * k[1], y = s.y + sn * k[0] + c * k[1];
    Frenet fc = track_.project(x, y, hint_);
    clearance = std::min({clearance, track_.wall_left_d(fc.seg, fc.u) - fc.d, fc.d - track_.wall_right_d(fc.seg, fc.u)});
  }
  last_wall_clearance_ = clearance;
  if (clearance < min_wall_clearance_) {
    min_wall_clearance_ = clearance;
    min_wall_clearance_s_ = f.s;
  }
  bool contact = clearance <= 0;
  if (contact && !in_contact_) { ++wall_contacts_; ev.wall_contact = true; }
  in_contact_ = contact;

  // Track limits: the middle of the car beyond an edge.
  const double mid = (fp_.front - fp_.rear) / 2;
  Frenet fm = track_.project(s.x + c * mid, s.y + sn * mid, hint_);
  bool outside = fm.d > track_.width_left(fm.seg, fm.u) || fm.d < -track_.width_right(fm.seg, fm.u);
  if (outside && !in_violation_) { ++track_violations_; ev.track_violation = true; }
  in_violation_ = outside;

  // Pylons: distance from the pylon's circle to the car's rectangle.
  const auto& pylons = track_.spec().pylons;
  for (std::size_t i = 0; i < pylons.size(); ++i) {
    const Pylon& p = pylons[i];
    double dx = p.x - s.x, dy = p.y - s.y;
    if (dx * dx + dy * dy > 60.0 * 60.0) continue;
    double bx = c * dx + sn * dy, by = -sn * dx + c * dy;  // body frame
    double ex = std::max({-fp_.rear - bx, bx - fp_.front, 0.0});
    double ey = std::max(std::abs(by) - fp_.half_width, 0.0);
    double gap = std::hypot(ex, ey) - p.radius;
    obstacle_min_clearance_ = std::min(obstacle_min_clearance_, gap);
    bool hit = gap <= 0;
    if (hit && !pylon_hit_[i]) { ++obstacles_hit_; ev.obstacle_hit = true; }
    pylon_hit_[i] = hit;
  }

  history_.push_back(s);
  while (history_.size() > 2 && history_.back().t - history_.front().t > 5.0) history_.pop_front();
  return ev;
}

bool Referee::localization(double t, double x, double y) {
  if (history_.empty() || t < history_.front().t - 1e-9 || t > history_.back().t + 1e-9) return false;
  auto it = std::lower_bound(history_.begin(), history_.end(), t, [](const TruthSample& a, double v) { return a.t < v; });
  double tx, ty;
  if (it == history_.begin() || it->t == t) {
    tx = it->x; ty = it->y;
  } else {
    auto a = std::prev(it);
    double w = (t - a->t) / (it->t - a->t);
    tx = a->x + (it->x - a->x) * w;
    ty = a->y + (it->y - a->y) * w;
  }
  double e = std::hypot(x - tx, y - ty);
  loc_sq_ += e * e;
  loc_max_ = std::max(loc_max_, e);
  ++loc_n_;
  return true;
}

double Referee::localization_rmse() const {
  return loc_n_ ? std::sqrt(loc_sq_ / static_cast<double>(loc_n_)) : std::numeric_limits<double>::quiet_NaN();
}
double Referee::localization_max_error() const {
  return loc_n_ ? loc_max_ : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace brickyard::sim
