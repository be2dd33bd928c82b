#pragma once
// The receivers' fixes of one epoch brought together when they come apart. On the real clock each
// receiver's fix is its own message, stamped when its receiver's step ran (a few milliseconds
// from the other's), and the estimator's step may take one before the other: as epochs of one
// fix each, the paper's update selection never weighs two receivers against each other, and
// coming back after an outage (reacquisition.hpp), which needs two that agree, never happens.
// A fix waits for the other receivers' fixes stamped within `pair_s` of it, or until the
// filter's clock is `wait_s` past its stamp (a receiver gone silent); then its epoch is handed
// on, each fix with its own stamp, and the localizer carries each to now by the car's motion
// since (Localizer::fixes). Framework-free.
#include "update_selection.hpp"

#include <deque>
#include <vector>

namespace brickyard::estimation {

struct GatheredEpoch {
  double t = 0;          // the latest of its fixes' stamps
  std::vector<Fix> fixes;  // each with its stamp
};

class EpochGather {
 public:
  EpochGather(int receivers, double pair_s, double wait_s) : receivers_(receivers), pair_s_(pair_s), wait_s_(wait_s) {}
  // One receiver's fix stamped `stamp`: joins the nearest held epoch within pair_s that has no
  // fix of its receiver yet, or starts one. A stamp that is not finite is refused (false).
  bool add(double stamp, Fix f);
  // The epochs that are whole (a fix of every receiver), or whose first fix is wait_s or more
  // before `now`, in the order of their first fix; and the oldest beyond kMaxHeld held (fixes
  // stamped ahead of the clock, forged or from a wrong clock, would otherwise wait for good).
  std::vector<GatheredEpoch> release(double now);
  std::size_t held() const { return held_.size(); }
  static constexpr std::size_t kMaxHeld = 16;

 private:
  int receivers_;
  double pair_s_, wait_s_;
  struct Held {
    double first = 0;
    GatheredEpoch epoch;
  };
  std::deque<Held> held_;
};

}  // namespace brickyard::estimation
