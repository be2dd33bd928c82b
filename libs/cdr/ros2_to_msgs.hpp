#pragma once
// ROS 2's sensor messages and odometry, read (ros2_pointcloud.hpp, ros2_sensors.hpp,
// ros2_state_msgs.hpp), into ours: what `bag play
// --map` and the replay.ros2_* plugins both do (docs/ros2.md). Templates over the message types, so
// this library stays free of the SDK's generated code. Header-only.
#include "cdr/cdr_reader.hpp"
#include "cdr/ros2_pointcloud.hpp"
#include "cdr/ros2_sensors.hpp"
#include "cdr/ros2_state_msgs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace brickyard::cdr {

// Where a cloud's sensor is: our PointCloud says it (ROS 2's says only a frame name).
struct CloudMount {
  int sensor_id = 0;
  std::array<double, 6> pose{};  // x, y, z (m), roll, pitch, yaw (rad) in the vehicle frame
};

// The cloud's columns moved into `out` (its old columns left in `c`: a player's next frame reuses them).
template <class PointCloud>
void to_point_cloud(CloudColumns& c, const CloudMount& mount, std::uint32_t seq, PointCloud& out) {
  out.header().stamp_ns(c.stamp_ns);
  out.header().seq(seq);
  out.header().frame_id(c.frame_id);
  out.sensor_id(static_cast<std::uint8_t>(mount.sensor_id));
  out.sensor_x(mount.pose[0]), out.sensor_y(mount.pose[1]), out.sensor_z(mount.pose[2]);
  out.sensor_roll(mount.pose[3]), out.sensor_pitch(mount.pose[4]), out.sensor_yaw(mount.pose[5]);
  out.x().swap(c.x), out.y().swap(c.y), out.z().swap(c.z);
  out.intensity().swap(c.intensity), out.time_offset().swap(c.time_offset);
}

// NavSatStatus to our fix_type: no fix 0; a fix, or one SBAS-augmented, single (1); GBAS (a
// ground station's corrections, as an RTK receiver's ROS driver reports them) fixed RTK (3).
inline std::uint8_t fix_type_of(std::int8_t status) { return status < 0 ? 0 : status == 2 ? 3 : 1; }

// A fix placed at `enu` (its latitude, longitude and altitude in the map frame: the caller's datum).
template <class GnssFix>
void to_gnss_fix(const NavSatFixValues& v, const std::array<double, 3>& enu, int receiver_id, std::uint32_t seq, GnssFix& out) {
  out.header().stamp_ns(v.stamp_ns);
  out.header().seq(seq);
  out.header().frame_id(v.frame_id);
  out.receiver_id(static_cast<std::uint8_t>(receiver_id));
  out.x(enu[0]), out.y(enu[1]), out.z(enu[2]);
  out.sigma_x(std::sqrt(std::max(0.0, v.position_covariance[0])));
  out.sigma_y(std::sqrt(std::max(0.0, v.position_covariance[4])));
  out.sigma_z(std::sqrt(std::max(0.0, v.position_covariance[8])));
  out.fix_type(fix_type_of(v.status));
  out.valid(v.status >= 0 && std::isfinite(v.latitude) && std::isfinite(v.longitude));
}

// Angular velocity and linear acceleration as they are (REP 103's axes are ours); the orientation unused.
template <class Imu>
void to_imu(const ImuValues& v, std::uint32_t seq, Imu& out) {
  out.header().stamp_ns(v.stamp_ns);
  out.header().seq(seq);
  out.header().frame_id(v.frame_id);
  out.accel_x(v.linear_acceleration[0]), out.accel_y(v.linear_acceleration[1]), out.accel_z(v.linear_acceleration[2]);
  out.gyro_x(v.angular_velocity[0]), out.gyro_y(v.angular_velocity[1]), out.gyro_z(v.angular_velocity[2]);
}

// A team's odometry (its localization) as our estimate: x, y and the heading in the plane; speed
// and yaw rate the twist's x and z (in child_frame_id, the car's, REP 105); the covariance over x,
// y and yaw taken from the pose's 6 x 6. No fusion stood behind it: update case 0, no deltas,
// status NORMAL.
template <class LocalizationEstimate>
void to_estimate(const Ros2Odometry& o, std::uint32_t seq, LocalizationEstimate& out) {
  out.header().stamp_ns(o.stamp_ns);
  out.header().seq(seq);
  out.header().frame_id(o.frame_id);
  out.x(o.pose.x), out.y(o.pose.y), out.yaw(yaw_of(o.pose.orientation));
  out.speed(o.linear[0]), out.yaw_rate(o.angular[2]);
  std::array<double, 9> c{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) c[r * 3 + k] = o.pose_covariance[kPlanarAxes[r] * 6 + kPlanarAxes[k]];
  out.covariance(c);
  out.update_case(0);
  out.status(0);
}

}  // namespace brickyard::cdr
