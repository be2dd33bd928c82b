#pragma once
// One sample of a ROS 2 bag (PointCloud2, NavSatFix, Imu, Odometry) into our message, for the replay.ros2_*
// plugins (ros2_plugin.cpp): the bytes read by cdr/ros2_*.hpp, the message filled as bag play
// --map fills it (cdr/ros2_to_msgs.hpp), a fix placed on the map by the GNSS drivers' datum.
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>

#include "cdr/ros2_to_msgs.hpp"
#include "drivers/common/local_datum.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace brickyard::replay {

// Each call throws std::invalid_argument when the bytes do not fit the type.
struct Ros2Converter {
  cdr::CloudMount mount;                   // a cloud's sensor (ROS 2's names only a frame)
  int receiver_id = 0;                     // a fix's receiver
  std::optional<drivers::LocalDatum> datum;  // a fix's map frame: required for NavSatFix
  cdr::CloudColumns columns;               // kept from sample to sample

  void operator()(const std::vector<unsigned char>& d, std::uint32_t seq, msgs::PointCloud& out) {
    cdr::read_pointcloud2(d.data(), d.size(), columns);
    cdr::to_point_cloud(columns, mount, seq, out);
  }
  void operator()(const std::vector<unsigned char>& d, std::uint32_t seq, msgs::GnssFix& out) {
    const cdr::NavSatFixValues v = cdr::read_navsatfix(d.data(), d.size());
    const Eigen::Vector3d enu = datum->to_map({v.latitude, v.longitude, v.altitude});
    cdr::to_gnss_fix(v, {enu.x(), enu.y(), enu.z()}, receiver_id, seq, out);
  }
  void operator()(const std::vector<unsigned char>& d, std::uint32_t seq, msgs::Imu& out) {
    cdr::to_imu(cdr::read_imu(d.data(), d.size()), seq, out);
  }
  void operator()(const std::vector<unsigned char>& d, std::uint32_t seq, msgs::LocalizationEstimate& out) {
    cdr::to_estimate(cdr::read_odometry(d.data(), d.size()), seq, out);
  }
};

}  // namespace brickyard::replay
