#pragma once
// Scores a localization estimate against ground truth around known fault windows: error (RMSE,
// max, max while the estimator said NORMAL), time to flag (first non-NORMAL status after a
// window opens), time to EMERGENCY, and false alarms (NORMAL -> not NORMAL away from any
// window). Given the estimate's own covariance, also whether it was honest: the error weighed by
// that covariance (NEES: about 2 on average for an honest 2-D estimate, above 13.8 one time in
// 1000), and the largest error where the estimate claimed to be sure (a confident wrong pose is
// what a witness must never give). Framework-free; sim.localization_scorer is its adapter.
#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

namespace brickyard::sim {

struct ScoreParams {
  std::vector<std::pair<double, double>> windows;  // fault windows [start, end), s
  double warmup_s = 5;                             // nothing counts before this
  double grace_s = 2;                              // after a window: recovery, not a false alarm
  double sure_sigma_m = 0.5;                       // an estimate whose largest 1-sigma is within this is sure
};

// An estimate's covariance over (x, y), m^2.
struct PlanarSpread {
  double xx = 0, xy = 0, yy = 0;
};

class LocalizationScore {
 public:
  explicit LocalizationScore(ScoreParams p) : p_(std::move(p)) {}
  void truth(double t, double x, double y);
  // status: 0 NORMAL, 1 WARNING, 2 EMERGENCY. False when t is outside the truth history.
  // `spread`: the estimate's covariance, when it is to be judged too (not positive definite:
  // the sample is not judged).
  bool estimate(double t, double x, double y, int status, const PlanarSpread* spread = nullptr);

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
  std::size_t judged() const { return nees_.size(); }  // samples with a spread
  double nees_p99() const;                             // NaN without judged samples
  double overconfident_share() const;                  // of judged samples, NEES above 13.8; NaN without
  double max_error_sure() const { return max_sure_; }  // the largest error with a largest sigma <= sure_sigma_m
  // The truth (x, y) the latest estimate() that returned true was scored against.
  std::pair<double, double> last_truth() const { return last_truth_; }

 private:
  bool in_window(double t, double grace) const;
  void judge(double ex, double ey, const PlanarSpread& spread);
  ScoreParams p_;
  std::deque<std::pair<double, std::pair<double, double>>> truth_;
  std::size_t n_ = 0;
  std::vector<double> errors_, nees_;
  double sq_ = 0, max_ = 0, max_sure_ = 0, max_normal_ = 0, max_window_ = 0, flag_ = -1, emergency_ = -1;
  int false_alarms_ = 0, last_status_ = 0;
  std::pair<double, double> last_truth_{0, 0};
};

// The score's figures as named metrics (the scorer plugin's).
std::vector<std::pair<const char*, double>> score_metrics(const LocalizationScore& s);

}  // namespace brickyard::sim
