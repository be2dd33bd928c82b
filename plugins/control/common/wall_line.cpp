#include "wall_line.hpp"

#include "mapped_wall.hpp"

#include "math/polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::control {

using math::poly_value;

bool usable(const WallView& w, int side, double max_distance) {
  if (!w.valid || w.coefficients.empty() || !(w.x_min <= w.x_max)) return false;
  for (double c : w.coefficients)
    if (!std::isfinite(c)) return false;
  return w.coefficients[0] * side > 0 && std::abs(w.coefficients[0]) <= max_distance;
}

namespace {

// Signed curvature of the wall y(x) as a curve along +x (left turns positive).
double wall_curvature(const WallView& w, double x) {
  const double d1 = poly_value(w.coefficients, x, 1), d2 = poly_value(w.coefficients, x, 2);
  return d2 / std::pow(1 + d1 * d1, 1.5);
}

}  // namespace

int choose_wall(int following, const WallView& left, const WallView& right, double max_distance) {
  const bool l = usable(left, 1, max_distance), r = usable(right, -1, max_distance);
  if (following > 0 && l) return 1;
  if (following < 0 && r) return -1;
  if (l && r) return std::abs(poly_value(left.coefficients, 0.0)) <= std::abs(poly_value(right.coefficients, 0.0)) ? 1 : -1;
  return l ? 1 : r ? -1 : 0;
}

double line_gap(const WallView& wall, int side, double distance, const WallLineParams& p) {
  double gap = std::clamp(distance, p.min_gap, std::max(p.max_gap, p.min_gap));
  // Inward is -side; a wall bending away from the car (side * kappa < 0: the outside of the
  // turn) gives the line inside it the curvature a / (1 - a gap), a = |kappa|.
  const double from = std::max(wall.x_min, 0.0), to = std::max(wall.x_max, from);
  for (double x = from; x <= to + 1e-9; x += p.step) {
    const double a = -side * wall_curvature(wall, x);
    if (a > 1e-6 && p.max_curvature > 0) gap = std::min(gap, 1.0 / a - 1.0 / p.max_curvature);
  }
  return std::max(gap, p.min_gap);
}

std::vector<PathPoint> offset_line(const WallView& wall, int side, double gap, double v_cap, const WallLineParams& p) {
  std::vector<PathPoint> line;
  const double left = -side * gap;  // the displacement to the left of the wall's direction
  const double step = std::max(p.step, 0.1);
  const double end = std::max(wall.x_max, 0.0);
  auto speed_at = [&](double kappa_line) {
    const double k = std::abs(kappa_line);
    return k > 1e-9 && p.a_lat > 0 ? std::min(v_cap, std::sqrt(p.a_lat / k)) : v_cap;
  };
  double tx = 1, ty = 0, v_end = v_cap;
  for (double x = -p.behind;; x = std::min(x + step, end)) {
    const double y = poly_value(wall.coefficients, x), d1 = poly_value(wall.coefficients, x, 1);
    const double n = std::hypot(1.0, d1);
    tx = 1 / n;
    ty = d1 / n;
    const double kw = wall_curvature(wall, x);
    const double denom = 1 - kw * left;  // a curve of curvature k moved left by d: k / (1 - k d)
    const double kl = denom > 1e-3 ? kw / denom : std::copysign(1e3, kw);
    v_end = speed_at(kl);
    line.push_back({x - left * ty, y + left * tx, v_end});
    if (x >= end) break;
  }
  // Past the wall's seen end: its tangent, at the speed of the tightest turn the line may take
  // (max_curvature): what the car cannot see may be a hairpin, so the tracker, braking ahead of
  // slower points, keeps the car within the distance it sees — the speed follows the sight.
  const PathPoint last = line.back();
  const double v_blind = std::min(v_end, speed_at(p.max_curvature));
  for (double d = step; d <= p.extend + 1e-9; d += step) line.push_back({last.x + d * tx, last.y + d * ty, v_blind});
  return line;
}

void LineOdometry::advance(double dt, double speed, double yaw_rate) {
  const double mid = yaw_ + 0.5 * yaw_rate * dt;
  x_ += speed * dt * std::cos(mid);
  y_ += speed * dt * std::sin(mid);
  yaw_ += yaw_rate * dt;
}

void MotionHistory::add(double t, double dt, double speed, double yaw_rate) {
  steps_.push_back({t, dt, speed, yaw_rate});
  if (steps_.size() > keep_) steps_.pop_front();
}

WallLineFollower::WallLineFollower(WallLineParams line, WallFollowerParams policy, TrackerParams tracker,
                                   RegistrationParams registration)
    : line_(line), policy_(policy), reg_params_(registration) {
  tracker.closed = false;  // a line of some tens of metres, never a loop
  tracker_ = PathTracker(tracker);
}

void WallLineFollower::engage(double t, double speed) {
  t0_ = t;
  v0_ = std::max(speed, policy_.restart_speed);
  rechoose_ = true;
}

double WallLineFollower::policy_speed(double t) const {
  if (!policy_.reduce_speed) return v0_;
  return std::max(std::min(v0_, policy_.fallback_speed), v0_ - policy_.decel * std::max(t - t0_, 0.0));
}

EdgeRegistration WallLineFollower::learnt(int side, double s) const {
  const auto& bins = base_[side > 0 ? 1 : 0];
  const long k = static_cast<long>(std::floor(s / std::max(line_.calibration_bin, 0.1)));
  auto it = bins.find(k);
  if (it != bins.end()) return it->second;
  // The nearest learnt bin within 5 bins; else the side's last.
  for (long d = 1; d <= 5; ++d) {
    if ((it = bins.find(k - d)) != bins.end()) return it->second;
    if ((it = bins.find(k + d)) != bins.end()) return it->second;
  }
  return last_base_[side > 0 ? 1 : 0];
}

void WallLineFollower::walls(double t, const WallView& left, const WallView& right, const std::vector<EdgePoint>* edge_left,
                             const std::vector<EdgePoint>* edge_right, const std::vector<PathPoint>* planned, double s_car,
                             bool calibrating) {
  if (calibrating) {
    const long k = static_cast<long>(std::floor(s_car / std::max(line_.calibration_bin, 0.1)));
    for (int i = 0; i < 2; ++i) {
      const std::vector<EdgePoint>* e = i ? edge_left : edge_right;
      const WallView& w = i ? left : right;
      if (!e || !usable(w, i ? 1 : -1, line_.max_distance)) continue;
      const EdgeRegistration r = register_edge(*e, w, reg_params_);
      if (!r.ok) continue;
      auto [it, added] = base_[i].emplace(k, r);
      if (!added) {  // a running mean of the frames in the bin, this lap and the last
        const double a = line_.registration_smoothing;
        it->second.shift += a * (r.shift - it->second.shift);
        it->second.turn += a * (r.turn - it->second.turn);
      }
      last_base_[i] = it->second;
    }
  }
  const bool fresh = rechoose_ || !has_line(t);
  const int s = choose_wall(fresh ? 0 : side_, left, right, line_.max_distance);
  if (s == 0) return;  // nothing seen: the last line is held (has_line) until hold_s
  const WallView& w = s > 0 ? left : right;
  const bool continued = s == side_ && reg_.ok && has_line(t);  // the last frame's registration holds for this wall
  if (fresh || s != side_) {
    if (!fresh) ++switches_;
    side_ = s;
    gap_ = std::abs(poly_value(w.coefficients, 0.0));  // the car's own distance: no lateral move
    rechoose_ = false;
  }
  const std::vector<EdgePoint>* edge = s > 0 ? edge_left : edge_right;
  reg_ = edge ? register_edge(*edge, w, reg_params_) : EdgeRegistration{};
  if (reg_.ok) {
    // The estimate drifts slowly; the fit of one frame is noisy: the correction is smoothed over
    // frames (a first-order filter, `registration_smoothing` of the new value per frame).
    if (continued) {
      const double a = line_.registration_smoothing;
      reg_.shift = smooth_.shift + a * (reg_.shift - smooth_.shift);
      reg_.turn = smooth_.turn + a * (reg_.turn - smooth_.turn);
    }
    smooth_ = reg_;
    if (planned && planned->size() >= 2) {
      // The planner's path, placed by the same estimate: what the registration corrects in the
      // edge's place it corrects in the path's. The car goes on along the line it was on.
      // Only the departure from the wall-to-edge registration learnt here is the estimate's.
      const EdgeRegistration base = learnt(s, s_car);
      EdgeRegistration drift;
      drift.shift = reg_.shift - base.shift;
      drift.turn = reg_.turn - base.turn;
      line_points_ = registered(*planned, drift);
      const double cap = policy_speed(t);
      for (PathPoint& q : line_points_) q.speed = std::min(q.speed, cap);
      ++planned_;
    } else {
      line_points_ = offset_polyline(registered(*edge, reg_), s, gap_, policy_speed(t), line_);
      ++mapped_;
    }
  } else {
    line_points_ = offset_line(w, s, line_gap(w, s, gap_, line_), policy_speed(t), line_);
    ++poly_;
  }
  tracker_.set_path(line_points_);
  odo_.reset();
  seen_t_ = t;
}

Command WallLineFollower::control(double t, double speed, double yaw_rate) {
  if (!has_line(t) || !tracker_.has_path()) {
    Command c;
    c.brake = 1;
    return c;
  }
  Command c = tracker_.control(CarState{odo_.x(), odo_.y(), odo_.yaw(), speed, yaw_rate, 0.0, t});
  // Never more steering than the tyres can turn into a turn at this speed (with a margin): a jump
  // of the line must not spin the car at 70 m/s, where 0.07 rad asks for five times its grip.
  const TrackerParams& tp = tracker_.params();
  if (tp.grip > 0 && speed > 1) {
    const double most = line_.grip_steer_margin * std::abs(steady_steer(tp.car, tp.grip / (speed * speed), speed));
    c.steer = std::clamp(c.steer, -most, most);
  }
  return c;
}

}  // namespace brickyard::control
