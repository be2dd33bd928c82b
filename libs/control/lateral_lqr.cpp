#include "lateral_lqr.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::control {
namespace {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;

// The discrete LQR gain of x' = A x + B u at speed v: iterate the Riccati difference equation to
// its fixed point (the pair is stabilisable for v > 0; a few hundred steps settle it).
std::array<double, 4> lqr_gain(const LateralModel& c, const LateralLqrParams& p, double v) {
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
  // Zero-order hold by the matrix exponential of the augmented system [A B; 0 0] T. Its norm
  // reaches about 5 at 3 m/s and 10 ms, so scale it below 1/2, sum the series, square back.
  using Mat5 = Eigen::Matrix<double, 5, 5>;
  Mat5 aug = Mat5::Zero();
  aug.topLeftCorner<4, 4>() = a * p.period;
  aug.topRightCorner<4, 1>() = b * p.period;
  int squarings = 0;
  for (double norm = aug.cwiseAbs().rowwise().sum().maxCoeff(); norm > 0.5; norm /= 2) ++squarings;
  aug /= std::ldexp(1.0, squarings);
  Mat5 e = Mat5::Identity(), term = e;
  for (int k = 1; k < 16; ++k) {  // 0.5^16 / 16!: far below double precision
    term = term * aug / k;
    e += term;
  }
  for (int i = 0; i < squarings; ++i) e = e * e;
  const Mat4 ad = e.topLeftCorner<4, 4>();
  const Vec4 bd = e.topRightCorner<4, 1>();
  Mat4 q = Mat4::Zero();
  q(0, 0) = p.q_lateral, q(1, 1) = p.q_lateral_rate, q(2, 2) = p.q_heading, q(3, 3) = p.q_heading_rate;
  Mat4 s = q;
  Eigen::RowVector4d k = Eigen::RowVector4d::Zero();
  for (int it = 0; it < 20000; ++it) {
    const double denom = p.r_steer + bd.dot(s * bd);
    const Eigen::RowVector4d kn = (bd.transpose() * s * ad) / denom;
    const Mat4 sn = q + ad.transpose() * s * (ad - bd * kn);
    const bool settled = (kn - k).cwiseAbs().maxCoeff() < 1e-10;
    k = kn;
    s = 0.5 * (sn + sn.transpose());
    if (settled) break;
  }
  return {k(0), k(1), k(2), k(3)};
}

}  // namespace

LateralLqr::LateralLqr(LateralModel car, LateralLqrParams p) : m_(car), p_(p) {
  if (!(car.mass > 0 && car.yaw_inertia > 0 && car.lf > 0 && car.lr > 0 && car.cornering_front > 0 && car.cornering_rear > 0))
    throw std::invalid_argument("lateral LQR: the car's mass, inertia, axle distances and cornering stiffnesses must be positive");
  if (!(p.period > 0 && p.v_min > 0 && p.v_max > p.v_min && p.v_step > 0 && p.r_steer > 0))
    throw std::invalid_argument("lateral LQR: period, speeds and the steering cost must be positive");
  for (double v = p.v_min; v <= p.v_max + 1e-9; v += p.v_step) table_.push_back(lqr_gain(m_, p_, v));
}

std::array<double, 4> LateralLqr::gains(double v) const {
  const double u = (std::clamp(v, p_.v_min, p_.v_max) - p_.v_min) / p_.v_step;
  const std::size_t i = std::min(static_cast<std::size_t>(u), table_.size() - 1), j = std::min(i + 1, table_.size() - 1);
  const double t = std::clamp(u - static_cast<double>(i), 0.0, 1.0);
  std::array<double, 4> k{};
  for (int n = 0; n < 4; ++n) k[n] = table_[i][n] + t * (table_[j][n] - table_[i][n]);
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

double LateralLqr::steer(const PathErrors& e, double kappa, double v) const {
  const auto k = gains(v);
  const double e_y = std::clamp(e.e_y, -p_.max_lateral_error, p_.max_lateral_error);
  const double x[4] = {e_y, e.e_y_rate, e.e_psi - steady_heading_error(kappa, v), e.e_psi_rate};
  double fb = 0;
  for (int n = 0; n < 4; ++n) fb -= k[n] * x[n];
  return feedforward(kappa, v) + fb;
}

}  // namespace brickyard::control
