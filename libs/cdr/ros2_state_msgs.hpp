#pragma once
// ROS 2's messages that draw a car in RViz and feed ROS 2 nodes its state, written as their CDR
// (ROS 2 Humble's definitions, cdr/ros2_std_types.hpp) without generated code:
// nav_msgs/msg/Odometry, geometry_msgs/msg/PoseStamped, tf2_msgs/msg/TFMessage and
// visualization_msgs/msg/MarkerArray (issue 45's bridge, docs/ros2.md). Each writes into `out`
// from its start, little-endian, the encapsulation header first; its memory kept. Odometry is
// read too (a team's bag through bag play --map and replay.ros2_odometry). Framework-free.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::cdr {

struct Quaternion {
  double x = 0, y = 0, z = 0, w = 1;
};
// Roll, pitch and yaw (rad; applied yaw, then pitch, then roll: REP 103's fixed axes x, y, z).
Quaternion quaternion_from_rpy(double roll, double pitch, double yaw);

struct Ros2Pose {
  double x = 0, y = 0, z = 0;
  Quaternion orientation;
};

// Where a planar pose's (x, y, yaw) stand among the axes of ROS 2's pose covariance (x, y, z, roll,
// pitch, yaw; 6 x 6 row-major): ours and theirs, both ways.
inline constexpr int kPlanarAxes[3] = {0, 1, 5};

struct Ros2Odometry {
  std::int64_t stamp_ns = 0;
  std::string frame_id, child_frame_id;
  Ros2Pose pose;
  std::array<double, 36> pose_covariance{};   // row-major over x, y, z, roll, pitch, yaw
  std::array<double, 3> linear{}, angular{};  // in child_frame_id: m/s, rad/s
  std::array<double, 36> twist_covariance{};
};
void write_odometry(const Ros2Odometry& o, std::vector<unsigned char>& out);
// An Odometry sample's CDR read (a team's bag, bag play --map; either byte order). A read past the
// end throws DamagedSample naming the field and byte (cdr_reader.hpp).
Ros2Odometry read_odometry(const unsigned char* cdr, std::size_t size);
// The heading a quaternion turns the x axis to in the x-y plane (rad, -pi to pi).
double yaw_of(const Quaternion& q);

void write_pose_stamped(std::int64_t stamp_ns, const std::string& frame_id, const Ros2Pose& pose, std::vector<unsigned char>& out);

// child_frame_id's pose in frame_id.
struct Ros2Transform {
  std::int64_t stamp_ns = 0;
  std::string frame_id, child_frame_id;
  double x = 0, y = 0, z = 0;
  Quaternion rotation;
};
void write_tf_message(const std::vector<Ros2Transform>& transforms, std::vector<unsigned char>& out);

// visualization_msgs/msg/Marker's types and actions used here.
enum MarkerType : std::int32_t { kMarkerCube = 1, kMarkerLineStrip = 4 };
enum MarkerAction : std::int32_t { kMarkerAdd = 0, kMarkerDeleteAll = 3 };
struct Ros2Marker {
  std::int64_t stamp_ns = 0;
  std::string frame_id, ns;
  std::int32_t id = 0, type = kMarkerCube, action = kMarkerAdd;
  Ros2Pose pose;
  std::array<double, 3> scale{1, 1, 1};
  std::array<float, 4> color{1, 1, 1, 1};  // r, g, b, a
  std::int64_t lifetime_ns = 0;            // 0: until replaced
  std::vector<std::array<double, 3>> points;
};
void write_marker_array(const std::vector<Ros2Marker>& markers, std::vector<unsigned char>& out);

}  // namespace brickyard::cdr
