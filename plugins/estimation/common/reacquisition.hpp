#pragma once
// Coming back after a long outage: when dead reckoning has drifted past δ, the
// resilient selection rejects every fix, healthy or not, for good. The rule that ends it: the
// receivers agree with each other (their base_link positions within `agree_m`) and with the
// motion model over `window_s` of consecutive rejected epochs: the path the fixes trace is the
// dead-reckoned path moved and turned, to within `motion_m` at every epoch (a rigid fit of the one
// onto the other, Eigen::umeyama). Dead reckoning drifts in position and heading together — a
// yaw-rate bias during the outage leaves a heading error behind it — so the turn is part of the
// rule, within `max_turn`. Then the filter takes the fixes' position and the heading the fit
// found. While the car has moved less than `min_span_m` the turn cannot be told and is taken as
// zero (the offset must then hold still). Framework-free.
//
// What it cannot tell: receivers that are wrong together, by the same offset (a common-mode
// error such as a wrong RTK base). The faults of this project's scenarios strike the receivers
// apart, and the paper's double failure differs by metres between them.
#include <Eigen/Core>

#include <deque>
#include <optional>
#include <vector>

namespace brickyard::estimation {

struct ReacquireParams {
  bool enabled = true;
  double agree_m = 0.3;    // m: the receivers' base_link positions within this of each other
  double motion_m = 0.3;   // m: the fitted dead-reckoned path within this of the fixes at every epoch
  double window_s = 1.0;   // s: both held this long
  double max_turn = 0.35;  // rad: the largest heading error the fit may correct
  double min_span_m = 5;   // m: the car must have moved this far in the window for a turn to count
  int min_receivers = 2;   // one receiver alone never re-acquires: nothing to agree with
};

struct Reacquired {
  Eigen::Vector2d position;  // base_link, the receivers' mean now
  double turn = 0;           // rad to add to the filter's heading
};

class Reacquisition {
 public:
  explicit Reacquisition(ReacquireParams p = {}) : p_(p) {}
  // One rejected epoch at time t: each receiver's base_link position and the filter's. Returns
  // the pose correction when the rule has held for the window (and starts over), else nothing.
  std::optional<Reacquired> observe(double t, const std::vector<Eigen::Vector2d>& fixes, const Eigen::Vector2d& filter);
  // An epoch that was not rejected: the rule starts over.
  void reset() { window_.clear(); }

 private:
  struct Sample {
    double t;
    Eigen::Vector2d fix, filter;
  };
  // The fit of the window's filter path onto its fixes, when it holds.
  std::optional<Reacquired> fit() const;
  ReacquireParams p_;
  std::deque<Sample> window_;
};

}  // namespace brickyard::estimation
