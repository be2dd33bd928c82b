#include "motion_check.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace brickyard::estimation {

std::deque<MotionSample>& MotionCheck::ring(int receiver) {
  const std::size_t i = receiver < 0 ? 0 : static_cast<std::size_t>(receiver);
  if (i >= rings_.size()) rings_.resize(i + 1);
  return rings_[i];
}

double MotionCheck::spread_along() const { return std::max(std::sqrt(var_along_), p_.spread_floor); }
double MotionCheck::spread_across() const { return std::max(std::sqrt(var_across_), p_.spread_floor); }

double MotionCheck::scale_sigma() const { return spread_along() / std::sqrt(std::max(1.0, learnt_s_ / p_.window_s)); }

double MotionCheck::wheel_scale() const {
  if (!enabled() || learnt_s_ < p_.learn_s || std::abs(scale_ - 1) <= 3 * scale_sigma()) return 1.0;
  return scale_;
}

MotionVerdict MotionCheck::observe(int receiver, const MotionSample& s) {
  MotionVerdict v;
  if (!enabled()) return v;
  auto& q = ring(receiver);
  // The window's start: the latest kept fix at least window_s old, and no older than a second
  // past it (a receiver back from an outage starts a new window).
  while (q.size() >= 2 && q[1].t <= s.t - p_.window_s) q.pop_front();
  const bool have = !q.empty() && q.front().t <= s.t - p_.window_s && q.front().t >= s.t - p_.window_s - 1.0;
  if (have) {
    const MotionSample& a = q.front();
    const Eigen::Vector2d dg = s.base - a.base;
    const Eigen::Vector2d dto = Eigen::Rotation2Dd(a.align) * (s.travel - a.travel);
    const double L = dto.norm();
    if (L >= p_.min_travel_m) {
      const Eigen::Vector2d u = dto / L, n(-u.y(), u.x());
      const double floor2 = p_.fix_floor * p_.fix_floor;
      const double fix_var = std::max(s.var, floor2) + std::max(a.var, floor2);
      const double sa = spread_along() * L, sc = spread_across() * L;
      const Eigen::Vector2d r = dg - scale_ * dto;
      v.window = true;
      v.scale = scale_;
      v.along = dg.dot(u) / L - scale_;
      v.across = dg.dot(n) / L;
      // Along the travel only: across it the sideslip model errs by a few tenths of a metre over
      // a window at a turn's entry (0.36 m over 112 m on a clean Hockenheim lap, five times the
      // mean spread), and the map tells the car's place across the road anyway.
      v.d2 = r.dot(u) * r.dot(u) / (sa * sa + fix_var);
      v.start_xy = a.filter_xy;
      v.travel = scale_ * dto;
      Eigen::Matrix2d B;
      B << u, n;
      v.travel_cov = B * Eigen::Vector2d(sa * sa, sc * sc).asDiagonal() * B.transpose();
      v.judged = learnt_s_ >= p_.learn_s;
      v.off = v.judged && v.d2 > p_.gate;
      if (v.judged) max_d2_ = std::max(max_d2_, v.d2);
    }
  }
  q.push_back(s);
  return v;
}

void MotionCheck::learn(double t, const MotionVerdict& v) {
  if (v.window && !v.off) pending_.push_back({t, v.along + v.scale, v.across});
  // A window is learnt once a window's length later nothing has been caught: a drift's first
  // windows, not yet past the gate, must not widen the spreads that would catch it.
  while (!pending_.empty() && pending_.front().t <= t - p_.window_s) {
    absorb(pending_.front());
    pending_.pop_front();
  }
}

void MotionCheck::forget_pending() { pending_.clear(); }

void MotionCheck::absorb(const Pending& w) {
  if (!started_) {
    // The first window: the scale starts from it.
    scale_ = w.ratio;
    started_ = true;
    last_learn_t_ = w.t;
    return;
  }
  const double dt = std::clamp(w.t - last_learn_t_, 0.0, 1.0);
  last_learn_t_ = w.t;
  // A plain mean over what is learnt until learn_tau_s of it, then exponential.
  const double a = std::min(1.0, dt / std::min(p_.learn_tau_s, learnt_s_ + dt));
  // The spread about the scale before this window moves it.
  const double along = w.ratio - scale_;
  var_along_ += a * (along * along - var_along_);
  var_across_ += a * (w.across * w.across - var_across_);
  scale_ += a * along;
  learnt_s_ += dt;
}

}  // namespace brickyard::estimation
