#pragma once
// One estimator step's samples handed to the Localizer in time order, framework-free. The plugin
// reads its inputs into these plain samples; the order of the calls they make is the estimate.
#include "epoch_gather.hpp"
#include "localizer.hpp"

#include <vector>

namespace brickyard::estimation {

struct ImuSample {
  double t = 0;  // s
  double gyro_z = 0, accel_y = 0;
};

struct GnssSample {
  double t = 0;        // s, the fix's stamp
  bool valid = false;  // false: "no fix", the receiver counts as silent
  Fix fix;
};

// A pose of base_link from another estimator (the scan mapper's LocalizationEstimate).
struct ScanPoseSample {
  double t = 0;         // s, the pose's stamp
  int update_case = 0;  // 2: registered on its map
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  Eigen::Matrix2d cov = Eigen::Matrix2d::Identity();
};

// The receivers an estimator is wired to and where their antennas sit.
struct Receivers {
  int count = 2;  // 1 or 2
  // Each receiver's antenna in base_link, m.
  Eigen::Vector3d lever[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  // A receiver's fix as the localizer takes it: an id other than 0 or 1, or any while one receiver
  // is wired, is the first receiver's; its spread is the larger of its two.
  Fix fix(int receiver_id, const Eigen::Vector2d& antenna, double sigma_x, double sigma_y) const;
};

// The IMU samples and fixes of one step in time order (an IMU sample before a fix of its stamp):
// each IMU sample closes the epoch of fixes before it, fixes of one stamp are one epoch. With
// `gather` (the real clock) the fixes go through it instead, and the epochs it lets go by the
// latest stamp of the step follow.
void feed_in_time_order(Localizer& loc, EpochGather* gather, const std::vector<ImuSample>& imu, const std::vector<GnssSample>& gnss);

// The scan mapper's poses, each of a LiDAR frame a sweep and a registration ago: only those it
// registered (update case 2); the localizer moves them to now.
void feed_scan_poses(Localizer& loc, const std::vector<ScanPoseSample>& poses);

}  // namespace brickyard::estimation
