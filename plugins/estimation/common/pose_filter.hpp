#pragma once
// Extended Kalman filter on the car's planar pose, framework-free. State (base_link = rear axle):
// x, y (m, map frame), yaw (rad), speed (m/s, along the body x axis), yaw rate (rad/s), and a
// sideslip gain K (s^2/m): the rear axle's lateral velocity is -K * speed^2 * yaw rate, the
// steady-state cornering of a single-track model with linear rear tyres (K = m l_f / (L C_r)).
// At 80 m/s in an IMS turn that sideslip is metres per second; dead reckoning without it drifts
// by tens of metres in seconds. K is learnt from the fixes (it shows only in turns, so it does not
// trade off against a heading error, which shows everywhere).
// Prediction takes the wheel speed and the gyro as the control input; corrections are positions
// of a GNSS antenna at a lever arm from base_link.
#include <Eigen/Core>

namespace brickyard::estimation {

struct FilterNoise {
  double speed = 0.05;       // m/s, 1 sigma of the wheel speed input
  double yaw_rate = 0.002;   // rad/s, of the gyro
  double position = 0.05;    // m/sqrt(s), process noise on x, y
  double yaw = 0.002;        // rad/sqrt(s)
  double slip_gain = 1e-4;   // s^2/m/sqrt(s): how fast the sideslip gain may change
  double min_sigma = 0.005;  // m: floor on a fix's reported sigma
};

class PoseFilter {
 public:
  static constexpr int N = 6;
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  enum : int { X = 0, Y, YAW, SPEED, YAW_RATE, SLIP };

  explicit PoseFilter(FilterNoise noise = {}) : noise_(noise) {}

  bool initialized() const { return initialized_; }
  void init(double x, double y, double yaw, double sigma_xy, double sigma_yaw);
  // Advance by dt with the control input (wheel speed, gyro yaw rate).
  void predict(double dt, double speed, double yaw_rate);

  // The body's roll (rad), for the lever arm: an antenna 1 m up moves 16 cm sideways on IMS's
  // 9.2 deg banking. Not a state: the plugin derives it from the IMU (docs/algorithms.md).
  void set_roll(double roll) { roll_ = roll; }
  double roll() const { return roll_; }
  // A fix of an antenna at `lever` (body frame, m) as a measurement of base_link: the position it
  // implies for base_link at the current yaw and roll, and the innovation's covariance P_xy + R.
  Eigen::Vector2d base_from_antenna(const Eigen::Vector2d& antenna, const Eigen::Vector3d& lever) const;
  Eigen::Matrix2d innovation_cov(const Eigen::Matrix2d& R) const { return P_.topLeftCorner<2, 2>() + R; }
  // Kalman update with a base_link position z and its covariance R.
  void update_position(const Eigen::Vector2d& z, const Eigen::Matrix2d& R);
  // The position z (covariance R) of a witness the filter had been pulled away from (fixes that
  // lied): the position's ties to the other states dropped (a metre's innovation through them
  // would kick the heading and the sideslip gain), its covariance widened by the distance to z,
  // then z taken. Where R is wide (a direction the witness cannot tell) the filter keeps its own.
  void relocate(const Eigen::Vector2d& z, const Eigen::Matrix2d& R);
  // Re-acquisition: the position is z (sigma m, uncorrelated with the rest); heading, speed, yaw
  // rate and sideslip gain keep their estimates.
  void reset_position(const Eigen::Vector2d& z, double sigma);
  // Re-acquisition with the heading corrected too: the position is z and the heading turns by
  // `turn` rad (its uncertainty kept); speed, yaw rate and sideslip gain keep their estimates.
  void reset_pose(const Eigen::Vector2d& z, double turn, double sigma);

  Eigen::Vector2d position() const { return x_.head<2>(); }
  double lateral_velocity() const { return -x_(SLIP) * x_(SPEED) * x_(SPEED) * x_(YAW_RATE); }
  const Vec& state() const { return x_; }
  const Mat& cov() const { return P_; }
  double fix_variance(double reported_sigma) const {
    const double s = reported_sigma > noise_.min_sigma ? reported_sigma : noise_.min_sigma;
    return s * s;
  }

 private:
  FilterNoise noise_;
  bool initialized_ = false;
  double roll_ = 0;
  Vec x_ = Vec::Zero();
  Mat P_ = Mat::Identity();
};

}  // namespace brickyard::estimation
