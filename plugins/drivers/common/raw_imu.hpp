#pragma once
// RAWIMUSX to the stack's IMU sample and back (the simulator's side), framework-free. A RAWIMUSX
// log carries velocity and angle increments in the IMU's counts, in the IMU body frame with its Y
// axis negated; times the IMU type's scale factors (NovAtel's "Raw IMU Scale Factors" table: per
// count, m/s and rad) they are increments, and times the IMU's output rate (100, 125, 200 or
// 400 Hz by model, RAWIMUSX's page) they are acceleration and rotation rate. The factors and rate
// are the fitted IMU's: parameters, never guessed (docs/drivers.md). The IMU's axes are turned into
// the vehicle's (x forward, y left, z up) by its mount.
#include "oem7_messages.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace brickyard::drivers {

struct RawImuScale {
  double accel_per_count = 0;  // m/s per count of a velocity increment
  double gyro_per_count = 0;   // rad per count of an angle increment
  double rate_hz = 0;          // the IMU's output rate
  Eigen::Matrix3d imu_to_vehicle = Eigen::Matrix3d::Identity();
  bool set() const { return accel_per_count > 0 && gyro_per_count > 0 && rate_hz > 0; }
};

struct ImuValues {
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // m/s^2, vehicle frame
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // rad/s, vehicle frame
  int64_t device_time_ns = 0;                       // GPS time of the sample, ns since 1980-01-06
  bool imu_error = false;                           // the IMU said it detected an error (IMU info bit 0)
};

// The IMU body frame's axes in the vehicle's, from its mount's roll, pitch and yaw (deg, applied
// yaw * pitch * roll, as the vehicle file's mounts).
Eigen::Matrix3d imu_mount(double roll_deg, double pitch_deg, double yaw_deg);

// Nothing when the scale is not set.
std::optional<ImuValues> imu_from(const RawImuSX& m, const RawImuScale& scale);
// The log a receiver would send for `v` (counts rounded to the nearest), its time v.device_time_ns.
RawImuSX raw_imu_of(const ImuValues& v, const RawImuScale& scale, uint8_t imu_type);

}  // namespace brickyard::drivers
