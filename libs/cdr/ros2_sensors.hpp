#pragma once
// ROS 2's sensor_msgs/msg/NavSatFix and sensor_msgs/msg/Imu, read from their CDR (a rosbag2 file's
// messages, docs/ros2.md) without generated code: the values a player turns into our GnssFix and
// Imu; and written (the bridge's, plugins/ros2). A sample that does not fit throws std::invalid_argument naming the message, field and byte.
// Framework-free.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::cdr {

struct NavSatFixValues {
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  std::int8_t status = -1;  // NavSatStatus: -1 no fix, 0 fix, 1 SBAS, 2 GBAS (ground-based augmentation: RTK)
  std::uint16_t service = 0;
  double latitude = 0, longitude = 0, altitude = 0;  // degrees, degrees, m above the WGS84 ellipsoid
  std::array<double, 9> position_covariance{};       // m^2, ENU, row-major
  std::uint8_t covariance_type = 0;                  // 0 unknown, 1 approximated, 2 diagonal known, 3 known
};
NavSatFixValues read_navsatfix(const unsigned char* cdr, std::size_t size);
// The same written as its CDR (little-endian, the encapsulation header first) into `out`.
void write_navsatfix(const NavSatFixValues& v, std::vector<unsigned char>& out);

struct ImuValues {
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  std::array<double, 4> orientation{};  // x, y, z, w
  std::array<double, 3> angular_velocity{}, linear_acceleration{};  // rad/s, m/s^2, the sensor's frame (REP 103: x forward, y left, z up)
  bool has_orientation = true;  // written: false says none (orientation_covariance[0] -1, REP 145)
};
ImuValues read_imu(const unsigned char* cdr, std::size_t size);
// The same written as its CDR; the covariances unknown (0), but the orientation's when it has none.
void write_imu(const ImuValues& v, std::vector<unsigned char>& out);

}  // namespace brickyard::cdr
