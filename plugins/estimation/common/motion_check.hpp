#pragma once
// A receiver whose fixes move unlike the car, framework-free. Both receivers drifting together
// (multipath), claiming RTK-fixed, agree with each other and, once the filter has followed them,
// with the prediction; along a straight whose walls do not say how far along the car is, the map
// cannot tell them either (docs/results-gnss-faults.md: the car in Monza's wall 12.9 s into such a
// drift). What the car's own motion says can: over the last window_s, each receiver's fixes
// travelled by Δg and dead reckoning (wheel speed, gyro, the filter's sideslip gain; never
// corrected) by Δo, laid into the map by the filter's heading at the window's start (the fixes
// pull the heading as they pull the position: the filter's own predictions turn with the drift
// and hide its part across the track); a receiver at the car's antenna moves as the car does,
// Δg ≈ s Δo, s the wheel speed's scale. The residual is judged along Δo against its spread
// (across it the map tells where the car is; the sideslip model errs there at a turn's entry):
//   learnt     while GNSS is healthy (every fix taken, no receiver caught), from the windows'
//              residuals, each a window_s after it with nothing caught meanwhile (a drift's
//              first windows must not widen what would catch it): the scale s and the relative
//              spreads along and across (a tyre's radius, slip, the sideslip model's error), each
//              their mean over the first learn_tau_s, then exponentially over learn_tau_s,
//              floored at spread_floor. Nothing is judged before learn_s of it. A car whose
//              odometry is poor learns a wide spread and is judged loosely: the check then
//              catches less, never more;
//   judged     a window of at least min_travel_m: the residual along the travel, squared, over
//              (spread x travel)^2 + the two fixes' variance, against gate.
// A fix judged off is the caller's to refuse (Localizer: only with a standing map, the witness
// left to race on). The car's position then is where the filter was at the window's start plus
// s Δo: the drift the filter took within the window undone.
#include <Eigen/Core>

#include <deque>
#include <vector>

namespace brickyard::estimation {

struct MotionParams {
  double window_s = 3.0;        // s of travel compared; 0: no check
  double gate = 10.83;          // chi-square, 1 dof, 0.999
  double min_travel_m = 20;     // m: a shorter window is neither judged nor learnt
  double learn_tau_s = 30;      // s: time constant of the learnt scale and spreads
  double learn_s = 20;          // s of healthy windows learnt before any is judged
  double spread_floor = 5e-4;   // relative: floor on the learnt spreads (0.05 % of the travel)
  double fix_floor = 0.05;      // m: floor on a fix's sigma
};

// One receiver's fix and what the car did up to it.
struct MotionSample {
  double t = 0;
  Eigen::Vector2d base;       // the fix as a position of base_link, m
  double var = 0;             // its variance, m^2
  Eigen::Vector2d travel;     // dead reckoning's position at t, m (its own frame)
  double align = 0;           // rad: the filter's heading less dead reckoning's at t
  Eigen::Vector2d filter_xy;  // the filter's position at t, m
};

struct MotionVerdict {
  bool judged = false;  // a window long enough, and enough learnt
  bool off = false;     // judged, and past the gate
  double d2 = 0;        // squared Mahalanobis distance
  // The window: its start's filter position, the travel since (scaled), and their covariance.
  Eigen::Vector2d start_xy = Eigen::Vector2d::Zero();
  Eigen::Vector2d travel = Eigen::Vector2d::Zero();
  Eigen::Matrix2d travel_cov = Eigen::Matrix2d::Identity();
  // The residual's relative parts along and across the travel, and the scale judged by (for learning).
  double along = 0, across = 0, scale = 1;
  bool window = false;  // a window long enough was found (judged or not)
};

class MotionCheck {
 public:
  explicit MotionCheck(MotionParams p) : p_(p) {}
  bool enabled() const { return p_.window_s > 0; }
  // A fix of `receiver`: kept for later windows, and judged against the one window_s before.
  MotionVerdict observe(int receiver, const MotionSample& s);
  // The fix of `v` was taken at t with GNSS healthy: its window is learnt from once window_s
  // has passed with nothing caught (forget_pending: something was).
  void learn(double t, const MotionVerdict& v);
  void forget_pending();

  double scale() const { return scale_; }
  // The learnt scale's own spread: the along spread over the root of the windows learnt (each
  // window_s long, taken as independent).
  double scale_sigma() const;
  // The scale to dead reckon with: the learnt one once learn_s is learnt and it differs from 1 by
  // more than three of its own spreads; else 1 (wheels as good as GNSS can tell: a scale of
  // 1.00003 learnt on IMS's true 1, taken, cost the map's outage 0.05 m at p99).
  double wheel_scale() const;
  double spread_along() const;
  double spread_across() const;
  double learnt_s() const { return learnt_s_; }
  double max_d2() const { return max_d2_; }  // the largest judged distance (a clean run's margin)

 private:
  std::deque<MotionSample>& ring(int receiver);
  struct Pending {
    double t, ratio, across;  // ratio: the fixes' travel along the car's over the car's
  };
  void absorb(const Pending& w);

  MotionParams p_;
  std::vector<std::deque<MotionSample>> rings_;
  std::deque<Pending> pending_;
  double var_along_ = 0, var_across_ = 0;
  double scale_ = 1, learnt_s_ = 0, last_learn_t_ = -1, max_d2_ = 0;
  bool started_ = false;
};

}  // namespace brickyard::estimation
