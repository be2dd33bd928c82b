#include "lateral_lqr.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::control {
namespace {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;
using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

// The errors' model at speed v, held over one period (zero-order hold): x' = ad x + bd delta.
void discrete_model(const LateralModel& c, double v, double period, Mat4& ad, Vec4& bd) {
  const double cf = c.cornering_front, cr = c.cornering_rear, m = c.mass, iz = c.yaw_inertia;
  Mat4 a = Mat4::Zero();
  a(0, 1) = 1;
  a(1, 1) = -(cf + cr) / (m * v);
  a(1, 2) = (cf + cr) / m;
  a(1, 3) = (-cf * c.lf + cr * c.lr) / (m * v);
  a(2, 3) = 1;
  a(3, 1) = -(cf * c.lf - cr * c.lr) / (iz * v);
  a(3, 2) = (cf * c.lf - cr * c.lr) / iz;
  a(3, 3) = -(cf * c.lf * c.lf + cr * c.lr * c.lr) / (iz * v);
  Vec4 b(0, cf / m, 0, cf * c.lf / iz);
  // The matrix exponential of the augmented system [A B; 0 0] T. Its norm reaches about 5 at
  // 3 m/s and 10 ms, so scale it below 1/2, sum the series, square back.
  using Mat5 = Eigen::Matrix<double, 5, 5>;
  Mat5 aug = Mat5::Zero();
  aug.topLeftCorner<4, 4>() = a * period;
  aug.topRightCorner<4, 1>() = b * period;
  int squarings = 0;
  for (double norm = aug.cwiseAbs().rowwise().sum().maxCoeff(); norm > 0.5; norm /= 2) ++squarings;
  aug /= std::ldexp(1.0, squarings);
  Mat5 e = Mat5::Identity(), term = e;
  for (int k = 1; k < 16; ++k) {  // 0.5^16 / 16!: far below double precision
    term = term * aug / k;
    e += term;
  }
  for (int i = 0; i < squarings; ++i) e = e * e;
  ad = e.topLeftCorner<4, 4>();
  bd = e.topRightCorner<4, 1>();
}

// The problem the gains solve: z' = a z + b u, cost z'q z + r u^2 + 2 z'n u per period.
struct Problem {
  Mat a, q;
  Vec b, n;
  double r = 0;
};

// The errors and the law's past outputs p_1..p_m (newest first): the road wheels take p_d, the
// output of d periods ago (the output itself when d is 0), and the rate's cost is on u - p_1.
Problem augmented(const Mat4& ad, const Vec4& bd, int d, int m, const LateralLqrParams& p) {
  const int dim = 4 + m;
  Problem pr;
  pr.a = Mat::Zero(dim, dim);
  pr.b = Vec::Zero(dim);
  pr.a.topLeftCorner<4, 4>() = ad;
  if (d > 0) pr.a.block<4, 1>(0, 4 + d - 1) = bd;
  else pr.b.head<4>() = bd;
  pr.b(4) = 1;  // p_1 <- u
  for (int j = 1; j < m; ++j) pr.a(4 + j, 4 + j - 1) = 1;  // p_j+1 <- p_j
  const double rate = p.r_steer_rate / (p.period * p.period);
  pr.q = Mat::Zero(dim, dim);
  pr.q(0, 0) = p.q_lateral, pr.q(1, 1) = p.q_lateral_rate, pr.q(2, 2) = p.q_heading, pr.q(3, 3) = p.q_heading_rate;
  pr.q(4, 4) = rate;
  pr.n = Vec::Zero(dim);
  pr.n(4) = -rate;
  pr.r = p.r_steer + rate;
  return pr;
}

// The discrete LQR gain: the stabilising solution of the Riccati equation by the doubling
// algorithm (quadratic convergence; no inverse of a, which the pipeline's shift makes singular),
// the cross term folded in first.
Vec lqr_gain(const Problem& pr) {
  const int dim = static_cast<int>(pr.b.size());
  const Mat id = Mat::Identity(dim, dim);
  Mat a = pr.a - pr.b * pr.n.transpose() / pr.r;
  Mat g = pr.b * pr.b.transpose() / pr.r;
  Mat h = pr.q - pr.n * pr.n.transpose() / pr.r;
  for (int it = 0; it < 100; ++it) {
    const Eigen::PartialPivLU<Mat> w(id + g * h);
    const Mat wa = w.solve(a), wg = w.solve(g);
    const Mat h_next = h + a.transpose() * h * wa;
    g = g + a * wg * a.transpose();
    a = a * wa;
    const bool settled = (h_next - h).cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, h_next.cwiseAbs().maxCoeff());
    h = 0.5 * (h_next + h_next.transpose());
    if (settled) break;
  }
  const double denom = pr.r + pr.b.dot(h * pr.b);
  return (pr.b.transpose() * h * pr.a + pr.n.transpose()).transpose() / denom;
}

}  // namespace

LateralLqr::LateralLqr(LateralModel car, LateralLqrParams p) : m_(car), p_(p) {
  if (!(car.mass > 0 && car.yaw_inertia > 0 && car.lf > 0 && car.lr > 0 && car.cornering_front > 0 && car.cornering_rear > 0))
    throw std::invalid_argument("lateral LQR: the car's mass, inertia, axle distances and cornering stiffnesses must be positive");
  if (!(p.period > 0 && p.v_min > 0 && p.v_max > p.v_min && p.v_step > 0 && p.r_steer > 0))
    throw std::invalid_argument("lateral LQR: period, speeds and the steering cost must be positive");
  if (!(p.delay >= 0 && p.delay <= kMaxPlannedDelay + 1e-9 && p.r_steer_rate >= 0))
    throw std::invalid_argument("lateral LQR: the delay must lie in [0, 0.3] s and the rate's cost be 0 or more");
  const int delay_steps = static_cast<int>(std::lround(p.delay / p.period));
  memory_ = std::max(delay_steps, 1);
  for (double v = p.v_min; v <= p.v_max + 1e-9; v += p.v_step) {
    Mat4 ad;
    Vec4 bd;
    discrete_model(m_, v, p.period, ad, bd);
    const Vec k = lqr_gain(augmented(ad, bd, delay_steps, memory_, p_));
    table_.emplace_back(k.data(), k.data() + k.size());
  }
}

std::vector<double> LateralLqr::gains(double v) const {
  const double u = (std::clamp(v, p_.v_min, p_.v_max) - p_.v_min) / p_.v_step;
  const std::size_t i = std::min(static_cast<std::size_t>(u), table_.size() - 1), j = std::min(i + 1, table_.size() - 1);
  const double t = std::clamp(u - static_cast<double>(i), 0.0, 1.0);
  std::vector<double> k(table_[i].size());
  for (std::size_t n = 0; n < k.size(); ++n) k[n] = table_[i][n] + t * (table_[j][n] - table_[i][n]);
  return k;
}

double steady_steer(const LateralModel& m, double kappa, double v) {
  const double l = m.lf + m.lr;
  const double kv = m.mass * (m.lr / m.cornering_front - m.lf / m.cornering_rear) / l;
  return l * kappa + kv * v * v * kappa;
}

double LateralLqr::feedforward(double kappa, double v) const { return steady_steer(m_, kappa, v); }

double LateralLqr::steady_heading_error(double kappa, double v) const {
  const double l = m_.lf + m_.lr;
  return -m_.lr * kappa + m_.lf * m_.mass * v * v * kappa / (m_.cornering_rear * l);
}

double LateralLqr::steer(const PathErrors& e, double kappa, double v, const std::vector<double>& past) const {
  const auto k = gains(v);
  const double e_y = std::clamp(e.e_y, -p_.max_lateral_error, p_.max_lateral_error);
  const double x[4] = {e_y, e.e_y_rate, e.e_psi - steady_heading_error(kappa, v), e.e_psi_rate};
  double fb = 0;
  for (int n = 0; n < 4; ++n) fb -= k[n] * x[n];
  for (std::size_t j = 0; j < past.size() && 4 + j < k.size(); ++j) fb -= k[4 + j] * past[j];
  return feedforward(kappa, v) + fb;
}

}  // namespace brickyard::control
