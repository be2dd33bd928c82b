#include "raw_imu.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace brickyard::drivers {

namespace {
constexpr int64_t kNsPerWeek = int64_t{604800} * 1000000000;

// The IMU body frame's axes from the log's (Y sent negated).
Eigen::Vector3d body(int32_t x, int32_t minus_y, int32_t z) {
  return {static_cast<double>(x), -static_cast<double>(minus_y), static_cast<double>(z)};
}

int32_t counts(double v) { return static_cast<int32_t>(std::llround(v)); }
}  // namespace

Eigen::Matrix3d imu_mount(double roll_deg, double pitch_deg, double yaw_deg) {
  constexpr double kDeg = M_PI / 180;
  return (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::optional<ImuValues> imu_from(const RawImuSX& m, const RawImuScale& scale) {
  if (!scale.set()) return std::nullopt;
  ImuValues v;
  const double a = scale.accel_per_count * scale.rate_hz, g = scale.gyro_per_count * scale.rate_hz;
  v.accel = scale.imu_to_vehicle * (a * body(m.accel_x_counts, m.accel_minus_y_counts, m.accel_z_counts));
  v.gyro = scale.imu_to_vehicle * (g * body(m.gyro_x_counts, m.gyro_minus_y_counts, m.gyro_z_counts));
  v.device_time_ns = m.gnss_week * kNsPerWeek + std::llround(m.gnss_seconds_of_week * 1e9);
  v.imu_error = (m.imu_info & 1) != 0;
  return v;
}

RawImuSX raw_imu_of(const ImuValues& v, const RawImuScale& scale, uint8_t imu_type) {
  RawImuSX m;
  m.header.framing = Oem7Framing::binary_short;
  m.imu_type = imu_type;
  m.imu_info = v.imu_error ? 1 : 0;
  m.gnss_week = static_cast<uint16_t>(v.device_time_ns / kNsPerWeek);
  m.gnss_seconds_of_week = static_cast<double>(v.device_time_ns % kNsPerWeek) * 1e-9;
  m.header.week = m.gnss_week;
  m.header.milliseconds = static_cast<uint32_t>((v.device_time_ns % kNsPerWeek) / 1000000);
  const Eigen::Matrix3d to_imu = scale.imu_to_vehicle.transpose();
  const Eigen::Vector3d a = to_imu * v.accel / (scale.accel_per_count * scale.rate_hz);
  const Eigen::Vector3d g = to_imu * v.gyro / (scale.gyro_per_count * scale.rate_hz);
  m.accel_x_counts = counts(a.x()), m.accel_minus_y_counts = counts(-a.y()), m.accel_z_counts = counts(a.z());
  m.gyro_x_counts = counts(g.x()), m.gyro_minus_y_counts = counts(-g.y()), m.gyro_z_counts = counts(g.z());
  return m;
}

}  // namespace brickyard::drivers
