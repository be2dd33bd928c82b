#include "pose_filter.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace brickyard::estimation {

void PoseFilter::init(double x, double y, double yaw, double sigma_xy, double sigma_yaw) {
  x_ = Vec::Zero();
  x_(X) = x;
  x_(Y) = y;
  x_(YAW) = yaw;
  P_ = Mat::Zero();
  P_(X, X) = P_(Y, Y) = sigma_xy * sigma_xy;
  P_(YAW, YAW) = sigma_yaw * sigma_yaw;
  P_(SPEED, SPEED) = noise_.speed * noise_.speed;
  P_(YAW_RATE, YAW_RATE) = noise_.yaw_rate * noise_.yaw_rate;
  P_(SLIP, SLIP) = 0.005 * 0.005;  // unknown: a race car's is a few 1e-3 s^2/m
  initialized_ = true;
}

void PoseFilter::predict(double dt, double speed, double yaw_rate) {
  if (!initialized_ || dt <= 0) return;
  // Speed and yaw rate are the control input: they replace the state's, with their noise.
  x_(SPEED) = speed;
  x_(YAW_RATE) = yaw_rate;
  P_.row(SPEED).setZero();
  P_.col(SPEED).setZero();
  P_.row(YAW_RATE).setZero();
  P_.col(YAW_RATE).setZero();
  P_(SPEED, SPEED) = noise_.speed * noise_.speed;
  P_(YAW_RATE, YAW_RATE) = noise_.yaw_rate * noise_.yaw_rate;

  // Integrate at the mid-point heading.
  const double yaw_mid = x_(YAW) + 0.5 * yaw_rate * dt;
  const double c = std::cos(yaw_mid), s = std::sin(yaw_mid);
  const double K = x_(SLIP), vx = speed, vy = -K * speed * speed * yaw_rate;
  const double dvy_dv = -2 * K * speed * yaw_rate, dvy_dw = -K * speed * speed, dvy_dk = -speed * speed * yaw_rate;
  Mat F = Mat::Identity();
  F(X, YAW) = (-s * vx - c * vy) * dt;
  F(Y, YAW) = (c * vx - s * vy) * dt;
  F(X, SPEED) = (c - s * dvy_dv) * dt;
  F(Y, SPEED) = (s + c * dvy_dv) * dt;
  F(X, YAW_RATE) = F(X, YAW) * 0.5 * dt - s * dvy_dw * dt;
  F(Y, YAW_RATE) = F(Y, YAW) * 0.5 * dt + c * dvy_dw * dt;
  F(YAW, YAW_RATE) = dt;
  F(X, SLIP) = -s * dvy_dk * dt;
  F(Y, SLIP) = c * dvy_dk * dt;
  x_(X) += (c * vx - s * vy) * dt;
  x_(Y) += (s * vx + c * vy) * dt;
  x_(YAW) = std::remainder(x_(YAW) + yaw_rate * dt, 2 * M_PI);
  P_ = F * P_ * F.transpose();
  P_(X, X) += noise_.position * noise_.position * dt;
  P_(Y, Y) += noise_.position * noise_.position * dt;
  P_(YAW, YAW) += noise_.yaw * noise_.yaw * dt;
  P_(SLIP, SLIP) += noise_.slip_gain * noise_.slip_gain * dt;
}

Eigen::Vector2d PoseFilter::base_from_antenna(const Eigen::Vector2d& antenna, const Eigen::Vector3d& lever) const {
  const double c = std::cos(x_(YAW)), s = std::sin(x_(YAW));
  // The lever arm's horizontal part after the roll (pitch is left out: under a degree here).
  const double lx = lever.x(), ly = lever.y() * std::cos(roll_) - lever.z() * std::sin(roll_);
  return antenna - Eigen::Vector2d(c * lx - s * ly, s * lx + c * ly);
}

void PoseFilter::update_position(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  if (!initialized_) return;
  const Eigen::Vector2d e = z - x_.head<2>();
  const Eigen::Matrix2d S = innovation_cov(R);
  // K = P H^T S^-1 with H = [I2 0]: the first two columns of P.
  const Eigen::Matrix<double, N, 2> K = P_.leftCols<2>() * S.inverse();
  x_ += K * e;
  x_(YAW) = std::remainder(x_(YAW), 2 * M_PI);
  // Joseph form keeps P symmetric and positive through many updates.
  Eigen::Matrix<double, 2, N> H = Eigen::Matrix<double, 2, N>::Zero();
  H(0, X) = H(1, Y) = 1;
  const Mat IKH = Mat::Identity() - K * H;
  P_ = IKH * P_ * IKH.transpose() + K * R * K.transpose();
}

void PoseFilter::reset_position(const Eigen::Vector2d& z, double sigma) {
  x_(X) = z.x();
  x_(Y) = z.y();
  P_.row(X).setZero();
  P_.row(Y).setZero();
  P_.col(X).setZero();
  P_.col(Y).setZero();
  P_(X, X) = P_(Y, Y) = sigma * sigma;
}

void PoseFilter::relocate(const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  if (!initialized_) return;
  const Eigen::Vector2d off = z - x_.head<2>();
  const Eigen::Matrix2d widened = P_.topLeftCorner<2, 2>() + off * off.transpose();
  P_.topRows<2>().setZero();
  P_.leftCols<2>().setZero();
  P_.topLeftCorner<2, 2>() = widened;
  update_position(z, R);
}

void PoseFilter::reset_pose(const Eigen::Vector2d& z, double turn, double sigma) {
  x_(YAW) = std::remainder(x_(YAW) + turn, 2 * M_PI);
  reset_position(z, sigma);
}

}  // namespace brickyard::estimation
