#pragma once
// What an estimator reports beside its estimate, framework-free: when its ModeStatus is due, how
// long it spent in each status, and the summary's metrics at the end of the run.
#include "localizer.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::estimation {

// The ModeStatus of one step, when one is due.
struct ModeDue {
  bool publish = false;   // due: the status changed, or 0.1 s have passed since the last
  bool announce = false;  // the status changed, or this is the first: the run's status line is told
  std::uint32_t seq = 0;  // the message's sequence number
};

// Called once per step with the time and the status: the time spent in each status (from one
// step to the next) and whether a ModeStatus is due, on a change and at 10 Hz.
class ModeCadence {
 public:
  ModeDue step(double now, Status s);
  double time_in(Status s) const { return time_in_[static_cast<int>(s)]; }

 private:
  double time_in_[3] = {0, 0, 0}, last_step_ = -1, last_mode_ = -1;
  Status last_status_ = Status::normal;
  std::uint32_t seq_ = 0;
};

// The summary's metrics of an estimator, in the order they are reported: the epochs and fixes,
// the time in WARNING and EMERGENCY, re-acquisitions (resilient), the scan poses (when wired),
// the map witness (when enabled) and the thresholds (resilient, for the report's delta figure).
std::vector<std::pair<std::string, double>> summary_metrics(const Localizer& loc, const ModeCadence& modes, Policy policy,
                                                            bool scan_pose_wired, const PolicyParams& selection);

}  // namespace brickyard::estimation
