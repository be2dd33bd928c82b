#pragma once
// Our messages as ROS 2's standard ones (issue 45; docs/ros2.md, "A bridge to ROS 2's tools"): what
// ros2.bridge publishes so that RViz and ROS 2 nodes see the car, its clouds, its path and what
// it found. Frames as REP 105 names them: ours "map" is the map frame, "vehicle" the base frame;
// a sensor's own frame keeps its name. Framework-free: unit tests call it directly.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/PointCloud.h>

#include "cdr/ros2_pointcloud.hpp"
#include "cdr/ros2_sensors.hpp"
#include "cdr/ros2_state_msgs.hpp"
#include "drivers/common/local_datum.hpp"

#include <string>
#include <vector>

namespace brickyard::ros2 {

struct Frames {
  std::string map = "map";        // REP 105's map frame: our "map"
  std::string base = "base_link";  // the car's: our "vehicle"
  // A message's frame as ROS 2 names it: "map" and "vehicle" by the names above (no frame: the
  // car's); a sensor's ("lidar_front") as it is.
  std::string of(const std::string& ours) const;
};

// An estimate's pose and speed: the car (base) in the map, a planar pose (z 0, level). Its
// covariance over x, y and yaw put in place; z, roll and pitch, which it does not estimate, a
// variance of 1e6 (REP 145's "unknown, large"); the twist's unknown (0).
cdr::Ros2Odometry odometry(const msgs::LocalizationEstimate& e, const Frames& f);
// The same pose as the map-to-base transform.
cdr::Ros2Transform map_to_base(const msgs::LocalizationEstimate& e, const Frames& f);
// Where a cloud's sensor sits on the car: the base-to-sensor transform, stamped as the cloud.
cdr::Ros2Transform base_to_sensor(const msgs::PointCloud& c, const Frames& f);
// A cloud's frame: its header's, or "lidar_N" by its sensor id when it names none.
std::string cloud_frame(const msgs::PointCloud& c, const Frames& f);
// The cloud's points in its sensor's frame.
void cloud_columns(const msgs::PointCloud& c, const Frames& f, cdr::CloudColumns& out);
// A path as one line strip (ns "path"), on the ground, in the path's frame.
std::vector<cdr::Ros2Marker> path_markers(const msgs::Path& p, const Frames& f);
// Obstacles as boxes (ns "obstacles", ids 0, 1, ...), after a DELETEALL that clears the last
// frame's: a marker array that says what this frame found, no more.
std::vector<cdr::Ros2Marker> obstacle_markers(const msgs::ObstacleList& o, const Frames& f);
// A fix back to latitude, longitude and height about the map frame's datum (GeographicLib, as the
// GNSS drivers place fixes); its sigmas a diagonal covariance; status: fixed RTK GBAS (2), single
// or float RTK a plain fix (0; bag play reads GBAS back as fixed RTK, a fix as single), none or
// invalid no fix (-1); service GPS. Its frame the antenna's: "gnss_N" by the receiver's id when
// ours names only the map.
void navsatfix_values(const msgs::GnssFix& f, const drivers::LocalDatum& datum, const Frames& frames, cdr::NavSatFixValues& out);
// An IMU sample (no orientation: the covariance's first element -1, REP 145).
void imu_values(const msgs::Imu& m, const Frames& f, cdr::ImuValues& out);

}  // namespace brickyard::ros2
