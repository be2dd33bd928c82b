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
// λk = 1 - Δk / ΣΔ over `use`, normalised to sum 1 (for two fixes the λ already sum to 1).
void weigh(const std::vector<double>& delta, const std::vector<int>& use, std::vector<double>& w) {
  double sum = 0;
  for (int i : use) sum += delta[i];
  if (use.size() == 1 || sum <= 0) {
    for (int i : use) w[i] = 1.0 / use.size();
    return;
  }
  double total = 0;
  for (int i : use) total += (w[i] = 1 - delta[i] / sum);
  for (int i : use) w[i] /= total;
}
}  // namespace

Selection select_updates(const std::vector<double>& delta, double epsilon, double delta_max) {
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
  } else if (all_eps || (n == 1)) {
    s.which = UpdateCase::single;
    s.weight[std::min_element(delta.begin(), delta.end()) - delta.begin()] = 1;
  } else if (static_cast<int>(within.size()) == n) {
    s.which = UpdateCase::weighted;
    weigh(delta, within, s.weight);
  } else {
    s.which = UpdateCase::partial;
    weigh(delta, within, s.weight);
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
  for (int i = 0; i < n; ++i) {
    z[i] = f.base_from_antenna(fixes[i].antenna, fixes[i].lever);
    R[i] = Eigen::Matrix2d::Identity() * f.fix_variance(fixes[i].sigma);
    r.delta[i] = metric_delta(z[i] - f.position(), f.innovation_cov(R[i]));
  }
  if (policy == Policy::resilient) {
    Selection s = select_updates(r.delta, p.epsilon, p.delta);
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
