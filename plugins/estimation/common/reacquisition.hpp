#pragma once
// Coming back after a long outage (issue 16): when dead reckoning has drifted past δ, the
// resilient selection rejects every fix, healthy or not, for good. The rule that ends it: the
// receivers agree with each other (their base_link positions within `agree_m`) and with the
// motion model (the offset of their mean from the dead-reckoned position stays within `motion_m`
// of where it was, i.e. the fixes move as the car is predicted to move) over `window_s` of
// consecutive rejected epochs. Then the filter takes the fixes' position. Framework-free.
//
// What it cannot tell: receivers that are wrong together, by the same offset (a common-mode
// error such as a wrong RTK base). The faults of this project's scenarios strike the receivers
// apart, and the paper's double failure differs by metres between them.
#include <Eigen/Core>

#include <optional>
#include <vector>

namespace brickyard::estimation {

struct ReacquireParams {
  bool enabled = true;
  double agree_m = 0.3;    // m: the receivers' base_link positions within this of each other
  double motion_m = 0.3;   // m: how far the fixes' offset from the prediction may wander
  double window_s = 1.0;   // s: both held this long
  int min_receivers = 2;   // one receiver alone never re-acquires: nothing to agree with
};

class Reacquisition {
 public:
  explicit Reacquisition(ReacquireParams p = {}) : p_(p) {}
  // One rejected epoch at time t: each receiver's base_link position and the filter's. Returns
  // the position to take when the rule has held for the window (and starts over), else nothing.
  std::optional<Eigen::Vector2d> observe(double t, const std::vector<Eigen::Vector2d>& fixes, const Eigen::Vector2d& filter);
  // An epoch that was not rejected: the rule starts over.
  void reset() { start_t_.reset(); }

 private:
  ReacquireParams p_;
  std::optional<double> start_t_;
  Eigen::Vector2d start_offset_ = Eigen::Vector2d::Zero();
};

}  // namespace brickyard::estimation
