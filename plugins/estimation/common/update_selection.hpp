#pragma once
// The paper's Bayesian update selection (§III-A) and the two baselines' update rules, on a
// PoseFilter, framework-free.
#include "pose_filter.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::estimation {

// What an epoch of fixes did to the filter (LocalizationEstimate.update_case).
enum class UpdateCase : std::uint8_t { predict_only = 0, single = 1, weighted = 2, partial = 3, rejected = 4 };

// The distance Δ of a fix to the prediction, in metres: the Mahalanobis distance of the
// innovation e under its covariance S, times S's largest standard deviation. It keeps S's shape
// (an error across the direction the prediction is sure of counts more) but is never less than
// the Euclidean distance, so ε and δ stay hard bounds in metres however far a long outage has
// inflated the covariance (the gate that a chi-square test would widen). See docs/algorithms.md.
double metric_delta(const Eigen::Vector2d& e, const Eigen::Matrix2d& S);

// The paper's four cases over the Δk of one epoch (ε < δ):
//   every Δk <= ε           -> single: the fix with the smallest Δ, weight 1;
//   every Δk <= δ           -> weighted: λk = 1 - Δk / ΣΔ, normalised to sum 1;
//   some Δk <= δ            -> partial: those (weighted as above among them when several);
//   none                    -> rejected: predict only.
// One fix alone within δ is used as it is (case single). Weights are 0 for unused fixes.
struct Selection {
  UpdateCase which = UpdateCase::predict_only;
  std::vector<double> weight;
};
Selection select_updates(const std::vector<double>& delta, double epsilon, double delta_max);

struct Fix {
  int receiver = 0;
  Eigen::Vector2d antenna;  // m, map frame
  Eigen::Vector2d lever;    // m, antenna in base_link (x, y)
  double sigma = 0;         // reported 1 sigma, m
};

enum class Policy { resilient, naive, gated };
struct PolicyParams {
  double epsilon = 0.2;       // m
  double delta = 5.0;         // m
  double gate_chi2 = 13.816;  // gated: chi-square, 2 dof, 99.9 %
};

struct EpochResult {
  UpdateCase which = UpdateCase::predict_only;
  std::vector<double> delta;   // per fix, metres (metric_delta)
  std::vector<bool> accepted;  // per fix: not rejected (resilient: within delta, used or not)
};

// Applies one epoch of fixes (at most one per receiver, all at the filter's time).
//   resilient: select_updates, then one update with the weighted position;
//   naive: every fix, one after another;
//   gated: every fix whose squared Mahalanobis distance under P + R passes gate_chi2 (the style
//          of robot_localization's rejection thresholds: after a long rejection P has grown
//          and bad fixes pass again).
EpochResult apply_fixes(PoseFilter& f, const std::vector<Fix>& fixes, Policy policy, const PolicyParams& p);

}  // namespace brickyard::estimation
