#pragma once
// `brickyard bag play BAG --map FILE`: which of a ROS 2 bag's topics (a team's own rosbag2 MCAP
// file, not a Brickyard recording) are played onto which wire, and what the conversion needs
// (docs/ros2.md). The file, JSON:
//   {"topics": {"/ouster/points": {"wire": "lidar_front.cloud", "sensor_id": 0,
//                                  "mount": {"x": 1.2, "y": 0, "z": 1.0, "roll": 0, "pitch": 0, "yaw": 0}},
//               "/gnss_left/fix": {"wire": "gnss_left.fix", "receiver_id": 0},
//               "/imu/data": {"wire": "imu.imu"}},
//    "datum": {"latitude": 39.793, "longitude": -86.238, "altitude": 220.0}}
// datum: the map frame's origin (WGS84, degrees, m above the ellipsoid), for NavSatFix topics.
// Anything else, or a value of the wrong kind or range: InvalidInput naming FILE#/pointer.
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw {

struct MappedTopic {
  std::string topic;  // the bag's, "/ouster/points"
  std::string wire;   // NODE.PORT
  int sensor_id = 0;  // PointCloud2: our cloud's sensor and its mount in the vehicle frame
  std::array<double, 6> mount{};  // x, y, z (m), roll, pitch, yaw (rad)
  int receiver_id = 0;  // NavSatFix
};

struct BagMap {
  std::string file;
  std::vector<MappedTopic> topics;
  std::optional<std::array<double, 3>> datum;  // latitude, longitude, altitude
};

BagMap read_bag_map(const std::string& path);

}  // namespace brickyard::fw
