#include "min_curvature.hpp"

#include "box_qp.hpp"
#include "track/curvature.hpp"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace brickyard::planning {

namespace {

struct Vec2 {
  double x, y;
};

double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

}  // namespace

OffsetFrame offset_frame(const ClosedLine& line, double margin, const char* who) {
  const int n = static_cast<int>(line.x.size());
  if (n < 4 || line.y.size() != line.x.size() || line.width_left.size() != line.x.size() || line.width_right.size() != line.x.size())
    throw std::invalid_argument(std::string(who) + ": needs at least 4 points with x, y and both widths each");
  OffsetFrame f;
  f.nx.resize(n), f.ny.resize(n), f.lo.resize(n), f.hi.resize(n);
  for (int i = 0; i < n; ++i) {
    // The unit tangent by central differences; the normal is it turned left.
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    const double dx = line.x[b] - line.x[a], dy = line.y[b] - line.y[a], l = std::max(std::hypot(dx, dy), 1e-12);
    f.nx[i] = -(dy / l);
    f.ny[i] = dx / l;
    f.lo[i] = -(line.width_right[i] - margin);
    f.hi[i] = line.width_left[i] - margin;
    if (f.lo[i] > f.hi[i]) f.lo[i] = f.hi[i] = 0.5 * (f.lo[i] + f.hi[i]);  // narrower than the car and margins: the middle
  }
  return f;
}

namespace {

// The input line's normals, the step h² at each point (the mean of its two sides, squared) and
// the box of the offsets.
struct LineGeometry {
  std::vector<Vec2> normal;
  std::vector<double> h2;
  Eigen::VectorXd lo, hi;
};

LineGeometry line_geometry(const ClosedLine& line, const OffsetFrame& frame) {
  const int n = static_cast<int>(line.x.size());
  LineGeometry geo{std::vector<Vec2>(n), std::vector<double>(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    const double h =
        0.5 * (std::hypot(line.x[b] - line.x[i], line.y[b] - line.y[i]) + std::hypot(line.x[i] - line.x[a], line.y[i] - line.y[a]));
    geo.h2[i] = h * h;
    geo.normal[i] = {frame.nx[i], frame.ny[i]};
    geo.lo(i) = frame.lo[i];
    geo.hi(i) = frame.hi[i];
  }
  return geo;
}

// The true objective, Σ κ_i², the curvature as the linearisation below writes it.
double objective(const ClosedLine& line, const LineGeometry& geo, const Eigen::VectorXd& al) {
  const int n = static_cast<int>(line.x.size());
  const std::vector<Vec2>& normal = geo.normal;
  const std::vector<double>& h2 = geo.h2;
  double f = 0;
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, c = (i + 1) % n;
    auto q = [&](int j) { return Vec2{line.x[j] + al(j) * normal[j].x, line.y[j] + al(j) * normal[j].y}; };
    const Vec2 qa = q(a), qi = q(i), qc = q(c);
    const double h = std::sqrt(h2[i]);
    const Vec2 q1{(qc.x - qa.x) / (2 * h), (qc.y - qa.y) / (2 * h)};
    const Vec2 q2{(qc.x - 2 * qi.x + qa.x) / h2[i], (qc.y - 2 * qi.y + qa.y) / h2[i]};
    const double s2 = q1.x * q1.x + q1.y * q1.y, k = cross(q1, q2) / (s2 * std::sqrt(s2));
    f += k * k * std::sqrt(s2) * h;  // κ² ds: ds = |q'| h
  }
  return f;
}

// The line's points at the offsets alpha.
void place(const ClosedLine& line, const LineGeometry& geo, const Eigen::VectorXd& alpha, MinCurvatureResult& r) {
  const int n = static_cast<int>(line.x.size());
  for (int i = 0; i < n; ++i) {
    r.x[i] = line.x[i] + alpha(i) * geo.normal[i].x;
    r.y[i] = line.y[i] + alpha(i) * geo.normal[i].y;
  }
}

// The residuals linearised at the current offsets: r ≈ b + M α.
struct Linearised {
  Eigen::SparseMatrix<double> M;
  Eigen::VectorXd b;
};

Linearised linearise(const LineGeometry& geo, const MinCurvatureResult& r, const Eigen::VectorXd& alpha) {
  const int n = static_cast<int>(r.x.size());
  const std::vector<Vec2>& normal = geo.normal;
  const std::vector<double>& h2 = geo.h2;
  // Gauss-Newton: κ_i = (q'_i × q''_i) / |q'_i|³ with q' and q'' central differences of
  // q_j = p_j + α_j n_j (linear in α), linearised at the current offsets: κ ≈ b + M α.
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, c = (i + 1) % n;
    const double h = std::sqrt(h2[i]);
    const Vec2 q1{(r.x[c] - r.x[a]) / (2 * h), (r.y[c] - r.y[a]) / (2 * h)};
    const Vec2 q2{(r.x[c] - 2 * r.x[i] + r.x[a]) / h2[i], (r.y[c] - 2 * r.y[i] + r.y[a]) / h2[i]};
    const double s2 = q1.x * q1.x + q1.y * q1.y, s3 = s2 * std::sqrt(s2), num = cross(q1, q2);
    const double k0 = num / s3;
    // The residual is κ √ds (ds = |q'| h, the arc length at the point), so the sum is Σ κ² ds,
    // the line's bending energy, as the comparison with TUM's lines measures. Its derivative
    // takes in that of √ds, or the Gauss-Newton step need not go downhill.
    const double speed = std::sqrt(s2), w = std::sqrt(speed * h);
    // d/dα_j of q' is n_j · d1_j, of q'' is n_j · d2_j.
    const int js[3] = {a, i, c};
    const double d1[3] = {-1 / (2 * h), 0, 1 / (2 * h)}, d2[3] = {1 / h2[i], -2 / h2[i], 1 / h2[i]};
    double lin = w * k0;
    for (int k = 0; k < 3; ++k) {
      const Vec2 nj = normal[js[k]];
      const double dnum = d1[k] * cross(nj, q2) + d2[k] * cross(q1, nj);
      const double ds2 = 2 * d1[k] * (q1.x * nj.x + q1.y * nj.y);
      const double dk = dnum / s3 - 1.5 * num * ds2 / (s3 * s2);
      const double dw = 0.25 * w * ds2 / s2;  // d√(|q'| h) = √(|q'| h) · d(|q'|²) / (4 |q'|²)
      const double dr = w * dk + k0 * dw;
      trip.emplace_back(i, js[k], dr);
      lin -= dr * alpha(js[k]);
    }
    b(i) = lin;
  }
  Linearised out{Eigen::SparseMatrix<double>(n, n), std::move(b)};
  out.M.setFromTriplets(trip.begin(), trip.end());
  return out;
}

// MᵀM with a touch of ridge: the curvature does not see every offset pattern (the Hessian is only
// semi-definite); 1e-9 of its scale picks the smallest offsets among equal curvatures.
Eigen::SparseMatrix<double> ridged_hessian(const Eigen::SparseMatrix<double>& M) {
  const int n = static_cast<int>(M.rows());
  Eigen::SparseMatrix<double> H = Eigen::SparseMatrix<double>(M.transpose()) * M;
  double scale = 0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, H.coeff(i, i));
  for (int i = 0; i < n; ++i) H.coeffRef(i, i) += 1e-9 * scale;
  return H;
}

// The linearisation may overshoot: step back along the way (the box is convex, so every point
// between stays inside it) until the true summed squared curvature goes down. False: no descent.
bool step_back_to_descent(const ClosedLine& line, const LineGeometry& geo, const Eigen::VectorXd& alpha, Eigen::VectorXd& step) {
  const double f0 = objective(line, geo, alpha);
  // (A non-finite value — points that coincide — counts as no descent.)
  auto worse = [&](const Eigen::VectorXd& a) { const double f = objective(line, geo, a); return !(f <= f0); };
  for (int k = 0; k < 20 && worse(alpha + step); ++k) step *= 0.5;
  return !worse(alpha + step);
}

}  // namespace

MinCurvatureResult min_curvature_line(const ClosedLine& line, const MinCurvatureParams& p) {
  const OffsetFrame frame = offset_frame(line, p.margin, "min_curvature_line");
  const int n = static_cast<int>(line.x.size());
  const LineGeometry geo = line_geometry(line, frame);
  MinCurvatureResult r;
  r.x = line.x;
  r.y = line.y;
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(n);
  if (!p.start.empty()) {
    if (static_cast<int>(p.start.size()) != n) throw std::invalid_argument("min_curvature_line: one start offset per point");
    for (int i = 0; i < n; ++i) alpha(i) = std::clamp(p.start[i], geo.lo(i), geo.hi(i));
    place(line, geo, alpha, r);
  }
  for (int it = 0; it < p.max_iterations; ++it) {
    const Linearised lin = linearise(geo, r, alpha);
    const Eigen::SparseMatrix<double> H = ridged_hessian(lin.M);
    const Eigen::VectorXd g = lin.M.transpose() * lin.b;
    Eigen::VectorXd next = alpha;
    r.active_set_rounds += box_qp(H, g, geo.lo, geo.hi, next);
    Eigen::VectorXd step = next - alpha;
    if (!step_back_to_descent(line, geo, alpha, step)) break;  // no descent left: converged
    const double moved = step.cwiseAbs().maxCoeff();
    alpha += step;
    place(line, geo, alpha, r);
    r.iterations = it + 1;
    if (moved < p.tolerance) break;
  }
  r.offset.assign(alpha.data(), alpha.data() + n);
  return r;
}

double summed_squared_curvature(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size());
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    double sides;
    const double k = track::menger_curvature(x[a], y[a], x[i], y[i], x[b], y[b], &sides);
    if (k != 0) sum += k * k * 0.5 * sides;
  }
  return sum;
}

}  // namespace brickyard::planning
