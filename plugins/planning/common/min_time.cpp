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

namespace {

void check_refine_inputs(const std::vector<double>& start, int n, const MinTimeParams& p) {
  if (!start.empty() && static_cast<int>(start.size()) != n)
    throw std::invalid_argument("min_time_refine: one start offset per point");
  if (!(p.curvature_slack >= 0) || !(p.smoothing > 0) || !std::isfinite(p.smoothing) || !(p.averaged_over >= 0) ||
      !std::isfinite(p.averaged_over) || p.max_iterations < 0 || !(p.tolerance >= 0))
    throw std::invalid_argument(
        "min_time_refine: needs curvature_slack >= 0, smoothing > 0, averaged_over >= 0, max_iterations >= 0, tolerance >= 0");
}

// The line's points at the offsets a.
void place(const ClosedLine& line, const OffsetFrame& f, const std::vector<double>& a, std::vector<double>& x, std::vector<double>& y) {
  const int n = static_cast<int>(line.x.size());
  x.resize(n), y.resize(n);
  for (int i = 0; i < n; ++i) x[i] = line.x[i] + a[i] * f.nx[i], y[i] = line.y[i] + a[i] * f.ny[i];
}

// The smoothing metric S = I + (ℓ/h)⁴ D₂ᵀD₂ (cyclic), fixed for the whole refinement.
Eigen::SparseMatrix<double> smoothing_metric(const ClosedLine& line, double smoothing) {
  const int n = static_cast<int>(line.x.size());
  double length = 0;
  for (int i = 0; i < n; ++i) length += std::hypot(line.x[(i + 1) % n] - line.x[i], line.y[(i + 1) % n] - line.y[i]);
  Eigen::SparseMatrix<double> S(n, n);
  const double w = std::pow(smoothing / (length / n), 4);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 1 + 6 * w);
    t.emplace_back(i, (i + 1) % n, -4 * w), t.emplace_back(i, (i + n - 1) % n, -4 * w);
    t.emplace_back(i, (i + 2) % n, w), t.emplace_back(i, (i + n - 2) % n, w);
  }
  S.setFromTriplets(t.begin(), t.end());  // duplicates (n < 5) add up, as D₂ᵀD₂ would
  return S;
}

// What a step is planned from, at the current offsets: the box of the step, g = dT/dα, and the
// residuals r with their Jacobian J; the profile's sensitivities besides.
struct LocalModel {
  explicit LocalModel(int n) : lo(n), hi(n), g(n), r(n), J(n, n) {}
  Eigen::VectorXd lo, hi, g, r;
  Eigen::SparseMatrix<double> J, JtJ;
  std::vector<double> ds, k, dk, dds;
};

// dT/dκ and dT/dds of the line as placed (T_p, and T_a when averaged) into m.dk and m.dds.
void lap_time_sensitivities(const MinTimeResult& res, const VehicleLimits& limits, const MinTimeParams& p, bool averaged,
                            LocalModel& m) {
  const int n = static_cast<int>(res.x.size());
  measure(res.x, res.y, m.ds, m.k);
  closed_lap_time_gradient(m.ds, m.k, limits, m.dk, m.dds);
  if (averaged) {
    // The averaged measure: T(ds, A κ) with A signed_curvature's moving average, so dT/dκ =
    // Aᵀ dT/d(Aκ) = A dT/d(Aκ) (A is symmetric); the steps enter as they are.
    const track::CenterLine now{"", res.x, res.y, {}, {}};
    std::vector<double> dka, ddsa;
    closed_lap_time_gradient(m.ds, track::signed_curvature(now, p.averaged_over), limits, dka, ddsa);
    dka = track::cyclic_average(dka, track::curvature_window(now, p.averaged_over));
    for (int i = 0; i < n; ++i) m.dk[i] += dka[i], m.dds[i] += ddsa[i];
  }
}

// g = dT/dα by the chain rule and J, the residuals' Jacobian: dκ/dα and dds/dα of the
// three-point formulas by central differences of the one point moved (only its neighbours'
// values change; the line search judges by the true lap time).
void offset_gradient(const MinTimeResult& res, const OffsetFrame& f, LocalModel& m) {
  const int n = static_cast<int>(res.x.size());
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
        gj += side * m.dk[(j + q + n) % n] * kq / (2 * h);
        trip.emplace_back((j + q + n) % n, j, side * rq / (2 * h));
      }
      gj += side * m.dds[(j + n - 1) % n] * std::hypot(x[2] - x[1], y[2] - y[1]) / (2 * h);
      gj += side * m.dds[j] * std::hypot(x[3] - x[2], y[3] - y[2]) / (2 * h);
    }
    m.g(j) = gj;
  }
  m.J.setFromTriplets(trip.begin(), trip.end());  // the two sides' entries add up
  m.JtJ = Eigen::SparseMatrix<double>(m.J.transpose()) * m.J;
}

// The residuals κ√ds at the current offsets, and the step's box lo − α ≤ d ≤ hi − α.
void residuals_and_box(const MinTimeResult& res, const OffsetFrame& f, const std::vector<double>& alpha, LocalModel& m) {
  const int n = static_cast<int>(res.x.size());
  for (int i = 0; i < n; ++i) {
    double kk, rr;
    menger(res.x[(i + n - 1) % n], res.y[(i + n - 1) % n], res.x[i], res.y[i], res.x[(i + 1) % n], res.y[(i + 1) % n], kk, rr);
    m.r(i) = rr;
    m.lo(i) = f.lo[i] - alpha[i];
    m.hi(i) = f.hi[i] - alpha[i];
  }
}

// The largest move of a free step of the smoothing metric alone, for the first ρ.
double free_step_size(const Eigen::SparseMatrix<double>& S, const Eigen::VectorXd& g) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(S);
  return (ldlt.solve(g)).cwiseAbs().maxCoeff();
}

// The step d of the QP  min gᵀd + ½ dᵀ(ρ S + 2ν JᵀJ) d + 2ν (Jᵀr)ᵀd in the model's box; the
// active-set rounds it took.
int qp_step(const Eigen::SparseMatrix<double>& S, const LocalModel& m, double rho, double nu, Eigen::VectorXd& d,
            std::vector<int>& bound) {
  Eigen::SparseMatrix<double> H = rho * S;
  Eigen::VectorXd lin = m.g;
  if (nu > 0) {
    H += 2 * nu * m.JtJ;
    lin += 2 * nu * (m.J.transpose() * m.r);
  }
  d.setZero();
  return box_qp(H, lin, m.lo, m.hi, d, &bound);
}

// The Gauss-Newton price ν after a step refused for its bending: from the scale where that term
// weighs as much as the metric, doubling on each such refusal.
double raised_bending_price(const LocalModel& m, double rho, double nu, int n) {
  double tr = 0;
  for (int c = 0; c < m.JtJ.outerSize(); ++c) tr += m.JtJ.coeff(c, c);
  return std::max(2 * nu, rho * n / (2 * std::max(tr, 1e-300)));
}

}  // namespace

MinTimeResult min_time_refine(const ClosedLine& line, const std::vector<double>& start, const VehicleLimits& limits,
                              const MinTimeParams& p) {
  const OffsetFrame f = offset_frame(line, p.margin, "min_time_refine");
  const int n = static_cast<int>(line.x.size());
  check_refine_inputs(start, n, p);
  std::vector<double> alpha(n, 0.0);
  for (int i = 0; i < n; ++i) alpha[i] = std::clamp(start.empty() ? 0.0 : start[i], f.lo[i], f.hi[i]);

  MinTimeResult res;
  place(line, f, alpha, res.x, res.y);
  const bool averaged = p.averaged_over > 0;
  res.start_time = res.time = lap_time(res.x, res.y, limits);
  res.start_averaged_time = res.averaged_time = averaged ? lap_time(res.x, res.y, limits, p.averaged_over) : 0.0;
  res.start_energy = res.energy = summed_squared_curvature(res.x, res.y);
  const double energy_max = res.start_energy * (1 + p.curvature_slack);
  const Eigen::SparseMatrix<double> S = smoothing_metric(line, p.smoothing);

  LocalModel m(n);
  Eigen::VectorXd d(n);
  std::vector<int> bound;  // the QP's bound set, a guess for the next
  double rho = -1, nu = 0;
  bool fresh = false;  // the model belongs to the current offsets
  std::vector<double> tx, ty;
  for (int it = 0; it < p.max_iterations; ++it) {
    if (!fresh) {
      lap_time_sensitivities(res, limits, p, averaged, m);
      offset_gradient(res, f, m);
      residuals_and_box(res, f, alpha, m);
      if (rho < 0) {
        // The first ρ: a free step of the smoothing metric alone would move the line 0.5 m at most.
        const double most = free_step_size(S, m.g);
        if (!(most > 0) || !std::isfinite(most)) break;  // nothing to gain (or nothing to measure)
        rho = most / 0.5;
      }
      fresh = true;
    }
    res.active_set_rounds += qp_step(S, m, rho, nu, d, bound);
    res.iterations = it + 1;
    if (d.cwiseAbs().maxCoeff() < 1e-4) break;  // steps of less than 0.1 mm: converged
    std::vector<double> next(n);
    for (int i = 0; i < n; ++i) next[i] = std::clamp(alpha[i] + d(i), f.lo[i], f.hi[i]);
    place(line, f, next, tx, ty);
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
      nu = raised_bending_price(m, rho, nu, n);  // faster but past the slack: price the bending
    } else {
      rho *= 4;
    }
  }
  res.offset = alpha;
  return res;
}

}  // namespace brickyard::planning
