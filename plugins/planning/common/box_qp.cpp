#include "box_qp.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <stdexcept>

namespace brickyard::planning {

int box_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
           Eigen::VectorXd& alpha, std::vector<int>* bound) {
  const int n = static_cast<int>(g.size());
  std::vector<int> state(n, 0);  // 0 free, -1 at lower, +1 at upper
  if (bound && static_cast<int>(bound->size()) == n) state = *bound;
  for (int i = 0; i < n; ++i) {
    alpha(i) = std::clamp(alpha(i), lo(i), hi(i));
    if (state[i] != 0) alpha(i) = state[i] < 0 ? lo(i) : hi(i);
    if (lo(i) == hi(i)) state[i] = -1;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  const int max_rounds = 4 * n + 50;
  for (int round = 1; round <= max_rounds; ++round) {
    std::vector<int> free_index(n, -1), free_vars;
    for (int i = 0; i < n; ++i)
      if (state[i] == 0) {
        free_index[i] = static_cast<int>(free_vars.size());
        free_vars.push_back(i);
      }
    const int m = static_cast<int>(free_vars.size());
    Eigen::VectorXd target = alpha;
    if (m > 0) {
      std::vector<Eigen::Triplet<double>> trip;
      Eigen::VectorXd rhs(m);
      for (int r = 0; r < m; ++r) rhs(r) = -g(free_vars[r]);
      for (int k = 0; k < H.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(H, k); it; ++it) {
          const int i = static_cast<int>(it.row()), j = static_cast<int>(it.col());
          if (free_index[i] < 0) continue;
          if (free_index[j] >= 0) trip.emplace_back(free_index[i], free_index[j], it.value());
          else rhs(free_index[i]) -= it.value() * alpha(j);
        }
      Eigen::SparseMatrix<double> Hf(m, m);
      Hf.setFromTriplets(trip.begin(), trip.end());
      ldlt.compute(Hf);
      if (ldlt.info() != Eigen::Success) throw std::runtime_error("box QP: the reduced system is singular");
      const Eigen::VectorXd sol = ldlt.solve(rhs);
      for (int r = 0; r < m; ++r) target(free_vars[r]) = sol(r);
    }
    // Step toward the target, stopping at the first bound met.
    double tau = 1;
    int blocking = -1;
    for (int i : free_vars) {
      const double d = target(i) - alpha(i);
      if (d < 0 && alpha(i) + d < lo(i)) {
        const double t = (lo(i) - alpha(i)) / d;
        if (t < tau) tau = t, blocking = i;
      } else if (d > 0 && alpha(i) + d > hi(i)) {
        const double t = (hi(i) - alpha(i)) / d;
        if (t < tau) tau = t, blocking = i;
      }
    }
    for (int i : free_vars) alpha(i) += tau * (target(i) - alpha(i));
    if (blocking >= 0) {
      state[blocking] = target(blocking) < lo(blocking) ? -1 : 1;
      alpha(blocking) = state[blocking] < 0 ? lo(blocking) : hi(blocking);
      continue;
    }
    // At the reduced optimum: release the bound variable the gradient pulls inside hardest.
    const Eigen::VectorXd grad = H * alpha + g;
    int release = -1;
    double most = 1e-12;
    for (int i = 0; i < n; ++i) {
      if (lo(i) == hi(i)) continue;
      const double pull = state[i] < 0 ? -grad(i) : state[i] > 0 ? grad(i) : 0.0;
      if (pull > most) most = pull, release = i;
    }
    if (release < 0) {
      if (bound) *bound = state;
      return round;
    }
    state[release] = 0;
  }
  if (bound) *bound = state;
  return max_rounds;
}

}  // namespace brickyard::planning
