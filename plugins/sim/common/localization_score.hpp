#pragma once
// Scores a localization estimate against ground truth around known fault windows: error (RMSE,
// max, max while the estimator said NORMAL), time to flag (first non-NORMAL status after a
// window opens), time to EMERGENCY, and false alarms (NORMAL -> not NORMAL away from any
// window). Framework-free; sim.localization_scorer is its adapter.
#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

namespace brickyard::sim {

struct ScoreParams {
  std::vector<std::pair<double, double>> windows;  // fault windows [start, end), s
  double warmup_s = 5;                             // nothing counts before this
  double grace_s = 2;                              // after a window: recovery, not a false alarm
};

class LocalizationScore {
 public:
  explicit LocalizationScore(ScoreParams p) : p_(std::move(p)) {}
  void truth(double t, double x, double y);
  // status: 0 NORMAL, 1 WARNING, 2 EMERGENCY. False when t is outside the truth history.
  bool estimate(double t, double x, double y, int status);

  std::size_t samples() const { return n_; }
  double rmse() const;                   // NaN without samples
  double p99_error() const;              // the 99th percentile of the errors; NaN without samples
  double max_error() const { return max_; }
  double max_error_normal() const { return max_normal_; }
  double time_to_flag() const { return flag_; }            // -1: never flagged in a window
  double time_to_emergency() const { return emergency_; }  // -1: never
  int false_alarms() const { return false_alarms_; }
  // The largest error in any fault window (from its start to its end): how far the estimate
  // drifted while the fault lasted. 0 without a window or a sample in one.
  double max_error_in_windows() const { return max_window_; }

 private:
  bool in_window(double t, double grace) const;
  ScoreParams p_;
  std::deque<std::pair<double, std::pair<double, double>>> truth_;
  std::size_t n_ = 0;
  std::vector<double> errors_;
  double sq_ = 0, max_ = 0, max_normal_ = 0, max_window_ = 0, flag_ = -1, emergency_ = -1;
  int false_alarms_ = 0, last_status_ = 0;
};

}  // namespace brickyard::sim
