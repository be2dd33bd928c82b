#include "update_selection.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace brickyard::estimation {

double metric_delta(const Eigen::Vector2d& e, const Eigen::Matrix2d& S) {
  if (!(S.determinant() > 0)) return e.norm();
  const double d2 = e.dot(S.ldlt().solve(e));
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(S, Eigen::EigenvaluesOnly).eigenvalues()(1);
  return std::sqrt(std::max(d2, 0.0) * largest);
}

namespace {
constexpr double kConsistent = 3.0;  // sigma

// Weights of the fixes in `use`, summing to 1.
//   paper: λk = 1 - Δk / ΣΔ, normalised (for two fixes the λ already sum to 1);
//   likelihood: exp(-max(0, d_k^2 - 3^2) / 2), normalised (shifted against underflow).
void weigh(const std::vector<double>& delta, const std::vector<int>& use, Weighting weighting,
           const std::vector<double>& mahalanobis, std::vector<double>& w) {
  if (use.size() == 1) {
    w[use[0]] = 1;
    return;
  }
  double total = 0;
  if (weighting == Weighting::likelihood && mahalanobis.size() == delta.size()) {
    // Fixes within kConsistent sigma count fully (equal R: the same update as fusing each in
    // turn, so no information is lost when all is well); beyond, the Gaussian tail.
    auto excess = [&](int i) { return std::max(0.0, mahalanobis[i] * mahalanobis[i] - kConsistent * kConsistent); };
    double least = excess(use[0]);
    for (int i : use) least = std::min(least, excess(i));
    for (int i : use) total += (w[i] = std::exp(-0.5 * (excess(i) - least)));
  } else {
    double sum = 0;
    for (int i : use) sum += delta[i];
    if (sum <= 0) {
      for (int i : use) w[i] = 1.0 / use.size();
      return;
    }
    for (int i : use) total += (w[i] = 1 - delta[i] / sum);
  }
  for (int i : use) w[i] /= total;
}
}  // namespace

Selection select_updates(const std::vector<double>& delta, double epsilon, double delta_max, Weighting weighting,
                         const std::vector<double>& mahalanobis) {
  Selection s;
  const int n = static_cast<int>(delta.size());
  s.weight.assign(n, 0.0);
  if (n == 0) return s;
  std::vector<int> within;
  bool all_eps = true;
  for (int i = 0; i < n; ++i) {
    if (delta[i] <= delta_max) within.push_back(i);
    all_eps = all_eps && delta[i] <= epsilon;
  }
  if (within.empty()) {
    s.which = UpdateCase::rejected;
  } else if (n == 1) {
    s.which = UpdateCase::single;
    s.weight[0] = 1;
  } else if (all_eps) {
    s.which = UpdateCase::single;
    if (weighting == Weighting::paper) {
      // The paper: use one of them (the closest).
      s.weight[std::min_element(delta.begin(), delta.end()) - delta.begin()] = 1;
    } else {
      // All of them by likelihood: two good receivers count as two (the same update as fusing
      // each in turn), and a noisy one that happens to fall within ε still counts for little.
      weigh(delta, within, weighting, mahalanobis, s.weight);
    }
  } else if (static_cast<int>(within.size()) == n) {
    s.which = UpdateCase::weighted;
    weigh(delta, within, weighting, mahalanobis, s.weight);
  } else {
    s.which = UpdateCase::partial;
    weigh(delta, within, weighting, mahalanobis, s.weight);
  }
  return s;
}

EpochResult apply_fixes(PoseFilter& f, const std::vector<Fix>& fixes, Policy policy, const PolicyParams& p) {
  EpochResult r;
  const int n = static_cast<int>(fixes.size());
  r.delta.resize(n);
  r.accepted.assign(n, false);
  if (n == 0 || !f.initialized()) return r;
  std::vector<Eigen::Vector2d> z(n);
  std::vector<Eigen::Matrix2d> R(n);
  std::vector<double> maha(n);
  for (int i = 0; i < n; ++i) {
    z[i] = f.base_from_antenna(fixes[i].antenna, fixes[i].lever);
    R[i] = Eigen::Matrix2d::Identity() * f.fix_variance(fixes[i].sigma);
    const Eigen::Vector2d e = z[i] - f.position();
    const Eigen::Matrix2d S = f.innovation_cov(R[i]);
    r.delta[i] = metric_delta(e, S);
    maha[i] = std::sqrt(std::max(0.0, e.dot(S.ldlt().solve(e))));
  }
  if (policy == Policy::resilient) {
    Selection s = select_updates(r.delta, p.epsilon, p.delta, p.weighting, maha);
    r.which = s.which;
    if (s.which == UpdateCase::rejected) return r;
    Eigen::Vector2d zf = Eigen::Vector2d::Zero();
    Eigen::Matrix2d Rf = Eigen::Matrix2d::Zero();
    for (int i = 0; i < n; ++i) {
      r.accepted[i] = r.delta[i] <= p.delta;  // qualified, if not the one used
      if (s.weight[i] <= 0) continue;
      zf += s.weight[i] * z[i];
      Rf += s.weight[i] * s.weight[i] * R[i];  // independent receivers
    }
    f.update_position(zf, Rf);
    return r;
  }
  int used = 0;
  for (int i = 0; i < n; ++i) {
    // Sequential updates: each fix is judged against the filter as the previous ones left it.
    const Eigen::Vector2d zi = f.base_from_antenna(fixes[i].antenna, fixes[i].lever);
    const Eigen::Vector2d e = zi - f.position();
    const Eigen::Matrix2d S = f.innovation_cov(R[i]);
    if (policy == Policy::gated && e.dot(S.ldlt().solve(e)) > p.gate_chi2) continue;
    f.update_position(zi, R[i]);
    r.accepted[i] = true;
    ++used;
  }
  r.which = used == 0 ? UpdateCase::rejected
            : used < n ? UpdateCase::partial
            : n == 1   ? UpdateCase::single
                       : UpdateCase::weighted;
  return r;
}

}  // namespace brickyard::estimation
