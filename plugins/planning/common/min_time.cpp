#include "min_time.hpp"

#include "box_qp.hpp"
#include "track/curvature.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::planning {

namespace {

// Menger curvature at b of the points a, b, c, and the residual κ √(½(|ab| + |bc|)) whose square
// is summed_squared_curvature's term.
void menger(double ax, double ay, double bx, double by, double cx, double cy, double& k, double& r) {
  double sides;
  k = track::menger_curvature(ax, ay, bx, by, cx, cy, &sides);
  r = k * std::sqrt(0.5 * sides);
}

// Steps and curvatures of a closed line, as lap_time() measures it.
void measure(const std::vector<double>& x, const std::vector<double>& y, std::vector<double>& ds, std::vector<double>& k) {
  const int n = static_cast<int>(x.size());
  ds.resize(n), k.resize(n);
  double r;
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    ds[i] = std::hypot(x[b] - x[i], y[b] - y[i]);
    menger(x[a], y[a], x[i], y[i], x[b], y[b], k[i], r);
  }
}

}  // namespace

LapProfile lap_profile(const std::vector<double>& x, const std::vector<double>& y, const VehicleLimits& limits,
                       double average_m) {
  if (x.size() < 3 || y.size() != x.size()) throw std::invalid_argument("lap_profile: needs at least 3 points with x and y each");
  LapProfile r;
  measure(x, y, r.ds, r.kappa);
  if (average_m > 0) r.kappa = track::signed_curvature(track::CenterLine{"", x, y, {}, {}}, average_m);
  r.v = speed_profile(r.ds, r.kappa, limits, true);
  r.time = profile_time(r.ds, r.v, true);
  return r;
}

double lap_time(const std::vector<double>& x, const std::vector<double>& y, const VehicleLimits& limits, double average_m) {
  return lap_profile(x, y, limits, average_m).time;
}

MinTimeResult min_time_refine(const ClosedLine& line, const std::vector<double>& start, const VehicleLimits& limits,
                              const MinTimeParams& p) {
  const OffsetFrame f = offset_frame(line, p.margin, "min_time_refine");
  const int n = static_cast<int>(line.x.size());
  if (!start.empty() && static_cast<int>(start.size()) != n)
    throw std::invalid_argument("min_time_refine: one start offset per point");
  if (!(p.curvature_slack >= 0) || !(p.smoothing > 0) || !std::isfinite(p.smoothing) || !(p.averaged_over >= 0) ||
      !std::isfinite(p.averaged_over) || p.max_iterations < 0 || !(p.tolerance >= 0))
    throw std::invalid_argument(
        "min_time_refine: needs curvature_slack >= 0, smoothing > 0, averaged_over >= 0, max_iterations >= 0, tolerance >= 0");
  std::vector<double> alpha(n, 0.0);
  for (int i = 0; i < n; ++i) alpha[i] = std::clamp(start.empty() ? 0.0 : start[i], f.lo[i], f.hi[i]);

  MinTimeResult res;
  auto place = [&](const std::vector<double>& a, std::vector<double>& x, std::vector<double>& y) {
    x.resize(n), y.resize(n);
    for (int i = 0; i < n; ++i) x[i] = line.x[i] + a[i] * f.nx[i], y[i] = line.y[i] + a[i] * f.ny[i];
  };
  place(alpha, res.x, res.y);
  const bool averaged = p.averaged_over > 0;
  res.start_time = res.time = lap_time(res.x, res.y, limits);
  res.start_averaged_time = res.averaged_time = averaged ? lap_time(res.x, res.y, limits, p.averaged_over) : 0.0;
  res.start_energy = res.energy = summed_squared_curvature(res.x, res.y);
  const double energy_max = res.start_energy * (1 + p.curvature_slack);

  // The smoothing metric S = I + (ℓ/h)⁴ D₂ᵀD₂ (cyclic), fixed for the whole refinement.
  double length = 0;
  for (int i = 0; i < n; ++i) length += std::hypot(line.x[(i + 1) % n] - line.x[i], line.y[(i + 1) % n] - line.y[i]);
  Eigen::SparseMatrix<double> S(n, n);
  {
    const double w = std::pow(p.smoothing / (length / n), 4);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 1 + 6 * w);
      t.emplace_back(i, (i + 1) % n, -4 * w), t.emplace_back(i, (i + n - 1) % n, -4 * w);
      t.emplace_back(i, (i + 2) % n, w), t.emplace_back(i, (i + n - 2) % n, w);
    }
    S.setFromTriplets(t.begin(), t.end());  // duplicates (n < 5) add up, as D₂ᵀD₂ would
  }

  Eigen::VectorXd lo(n), hi(n), g(n), r(n), d(n);
  Eigen::SparseMatrix<double> J(n, n), JtJ;
  std::vector<int> bound;  // the QP's bound set, a guess for the next
  double rho = -1, nu = 0;
  bool fresh = false;  // g, J, r belong to the current offsets
  std::vector<double> ds, k, dk, dds, tx, ty;
  for (int it = 0; it < p.max_iterations; ++it) {
    if (!fresh) {
      // dT/dα by the chain rule: dT/dκ and dT/dds from the profile, dκ/dα and dds/dα of the
      // three-point formulas by central differences of the one point moved (only its neighbours'
      // values change; the line search judges by the true lap time).
      measure(res.x, res.y, ds, k);
      closed_lap_time_gradient(ds, k, limits, dk, dds);
      if (averaged) {
        // The averaged measure: T(ds, A κ) with A signed_curvature's moving average, so dT/dκ =
        // Aᵀ dT/d(Aκ) = A dT/d(Aκ) (A is symmetric); the steps enter as they are.
        const track::CenterLine now{"", res.x, res.y, {}, {}};
        std::vector<double> dka, ddsa;
        closed_lap_time_gradient(ds, track::signed_curvature(now, p.averaged_over), limits, dka, ddsa);
        dka = track::cyclic_average(dka, track::curvature_window(now, p.averaged_over));
        for (int i = 0; i < n; ++i) dk[i] += dka[i], dds[i] += ddsa[i];
      }
      std::vector<Eigen::Triplet<double>> trip;
      const double h = 1e-5;
      for (int j = 0; j < n; ++j) {
        double gj = 0;
        double x[5], y[5];  // points j-2 .. j+2
        for (int q = -2; q <= 2; ++q) x[q + 2] = res.x[(j + q + 2 * n) % n], y[q + 2] = res.y[(j + q + 2 * n) % n];
        for (int side = -1; side <= 1; side += 2) {
          x[2] = res.x[j] + side * h * f.nx[j], y[2] = res.y[j] + side * h * f.ny[j];
          for (int q = -1; q <= 1; ++q) {
            double kq, rq;
            menger(x[q + 1], y[q + 1], x[q + 2], y[q + 2], x[q + 3], y[q + 3], kq, rq);
            gj += side * dk[(j + q + n) % n] * kq / (2 * h);
            trip.emplace_back((j + q + n) % n, j, side * rq / (2 * h));
          }
          gj += side * dds[(j + n - 1) % n] * std::hypot(x[2] - x[1], y[2] - y[1]) / (2 * h);
          gj += side * dds[j] * std::hypot(x[3] - x[2], y[3] - y[2]) / (2 * h);
        }
        g(j) = gj;
      }
      J.setFromTriplets(trip.begin(), trip.end());  // the two sides' entries add up
      JtJ = Eigen::SparseMatrix<double>(J.transpose()) * J;
      for (int i = 0; i < n; ++i) {
        double kk, rr;
        menger(res.x[(i + n - 1) % n], res.y[(i + n - 1) % n], res.x[i], res.y[i], res.x[(i + 1) % n], res.y[(i + 1) % n], kk, rr);
        r(i) = rr;
        lo(i) = f.lo[i] - alpha[i];
        hi(i) = f.hi[i] - alpha[i];
      }
      if (rho < 0) {
        // The first ρ: a free step of the smoothing metric alone would move the line 0.5 m at most.
        Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(S);
        const double most = (ldlt.solve(g)).cwiseAbs().maxCoeff();
        if (!(most > 0) || !std::isfinite(most)) break;  // nothing to gain (or nothing to measure)
        rho = most / 0.5;
      }
      fresh = true;
    }
    Eigen::SparseMatrix<double> H = rho * S;
    Eigen::VectorXd lin = g;
    if (nu > 0) {
      H += 2 * nu * JtJ;
      lin += 2 * nu * (J.transpose() * r);
    }
    d.setZero();
    res.active_set_rounds += box_qp(H, lin, lo, hi, d, &bound);
    res.iterations = it + 1;
    if (d.cwiseAbs().maxCoeff() < 1e-4) break;  // steps of less than 0.1 mm: converged
    std::vector<double> next(n);
    for (int i = 0; i < n; ++i) next[i] = std::clamp(alpha[i] + d(i), f.lo[i], f.hi[i]);
    place(next, tx, ty);
    const double t = lap_time(tx, ty, limits), ta = averaged ? lap_time(tx, ty, limits, p.averaged_over) : 0.0;
    const double e = summed_squared_curvature(tx, ty);
    // Faster: the objective T_p + T_a goes down and neither measure gets worse.
    const double gain = (res.time + res.averaged_time) - (t + ta);
    const bool faster = gain > 0 && t <= res.time && ta <= res.averaged_time;
    if (faster && e <= energy_max) {
      alpha.swap(next), res.x.swap(tx), res.y.swap(ty);
      res.time = t, res.averaged_time = ta, res.energy = e;
      ++res.accepted;
      fresh = false;
      rho *= 0.5;
      if (gain < p.tolerance) break;
    } else if (faster) {
      // Faster but past the slack: price the bending (ν from the scale where the Gauss-Newton
      // term weighs as much as the metric, doubling on each such refusal).
      double tr = 0;
      for (int c = 0; c < JtJ.outerSize(); ++c) tr += JtJ.coeff(c, c);
      nu = std::max(2 * nu, rho * n / (2 * std::max(tr, 1e-300)));
    } else {
      rho *= 4;
    }
  }
  res.offset = alpha;
  return res;
}

}  // namespace brickyard::planning
