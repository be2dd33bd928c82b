#pragma once
// ROS 2's standard message types that Brickyard writes at its edges (issue 45; docs/ros2.md, "A
// ROS 2 bridge"), as OMG IDL in ROS 2 Humble's definitions (common_interfaces 4.2, the
// distribution IAC teams race; the same bytes in later ones but for what they added):
// nav_msgs::msg::Odometry, geometry_msgs::msg::PoseStamped, tf2_msgs::msg::TFMessage,
// visualization_msgs::msg::MarkerArray, sensor_msgs::msg::PointCloud2, Imu and NavSatFix. The
// host carries them as CDR it does not decode (a port of such a type is written by a plugin as
// bytes); the IDL is what a recording's schema, `topic echo` and a ROS 2 bag's ros2msg schema are
// made from. Framework-free.
#include <string>
#include <vector>

namespace brickyard::cdr {

// The type's IDL, its own module block first and then each type it uses, depth first (the form
// the recorder's omgidl_schema takes: reversed, each definition after what it uses); null when
// `type` ("nav_msgs::msg::Odometry") is not one of them.
const char* ros2_standard_idl(const std::string& type);

// The top-level types above, qualified.
const std::vector<std::string>& ros2_standard_types();

}  // namespace brickyard::cdr
