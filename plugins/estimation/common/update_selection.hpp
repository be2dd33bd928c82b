#pragma once
// The paper's Bayesian update selection (§III-A) and the two baselines' update rules, on a
// PoseFilter, framework-free.
#include "pose_filter.hpp"

#include <cstdint>
#include <limits>
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
//   every Δk <= ε           -> single: paper weighting: the closest fix alone, as the paper does;
//                              likelihood: all of them, weighted by likelihood;
//   every Δk <= δ           -> weighted: λk = 1 - Δk / ΣΔ, normalised to sum 1;
//   some Δk <= δ            -> partial: those (weighted as above among them when several);
//   none                    -> rejected: predict only.
// One fix alone within δ is used as it is (case single). Weights are 0 for unused fixes.
// How the weighted cases weigh the fixes they use.
//   likelihood: λk ∝ exp(-max(0, d_k^2 - 9) / 2), d_k the Mahalanobis distance of fix k: the
//               paper's own p(θk | x) ≜ -Δk read as a log-likelihood, flat within 3 sigma so
//               consistent receivers count equally (the plugin's default);
//   paper:      λk = 1 - Δk / ΣΔ, the paper's formula. Between two disagreeing receivers it has
//               no preference and drifts to the faulty one (docs/algorithms.md).
enum class Weighting { paper, likelihood };

struct Selection {
  UpdateCase which = UpdateCase::predict_only;
  std::vector<double> weight;
};
// `mahalanobis` (d_k, unitless) is needed for Weighting::likelihood only.
Selection select_updates(const std::vector<double>& delta, double epsilon, double delta_max,
                         Weighting weighting = Weighting::paper, const std::vector<double>& mahalanobis = {});

struct Fix {
  int receiver = 0;
  Eigen::Vector2d antenna;  // m, map frame
  Eigen::Vector3d lever;    // m, antenna in base_link
  double sigma = 0;         // reported 1 sigma, m
  double stamp = std::numeric_limits<double>::quiet_NaN();  // s; NaN: the epoch's (Localizer::fixes)
};

enum class Policy { resilient, naive, gated };
struct PolicyParams {
  double epsilon = 0.2;       // m
  double delta = 5.0;         // m
  double gate_chi2 = 13.816;  // gated: chi-square, 2 dof, 99.9 %
  Weighting weighting = Weighting::likelihood;
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
