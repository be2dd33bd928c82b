#pragma once
// mapping.scan_mapper's ports (plugin.cpp): the ground filter's frames, the estimate, the LiDARs'
// raw returns and the IMU; the pose found. Plugin-side (SDK).
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include <array>

namespace brickyard::mapping {

constexpr int kScans = 4;  // LiDARs whose raw returns the road surface may take

struct Ports {
  Input<msgs::PointCloud> points, ground;
  Input<msgs::LocalizationEstimate> estimate;
  std::array<Input<msgs::PointCloud>, kScans> scan;
  Input<msgs::Imu> imu;
  Output<msgs::LocalizationEstimate> pose;
};

inline PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("points", &Ports::points).doc("the ground filter's vertical features, vehicle frame").depth(8);
  b.input("ground", &Ports::ground).doc("the ground filter's ground, vehicle frame, the same frames").depth(8).steps();
  b.input("estimate", &Ports::estimate).doc("the pose estimate (the fusion's), its covariance the prior").depth(64);
  b.inputs("scan", &Ports::scan)
      .doc("a LiDAR's raw returns with their intensities (sensor frame): the road surface").optional().depth(8);
  b.input("imu", &Ports::imu).doc("the IMU (specific force, yaw rate): gravity, the map's level (with level_on_ground)")
      .optional().depth(64);
  b.output("pose", &Ports::pose).doc("the pose found, stamped with the frame; covariance over (x, y, yaw)");
  return b;
}

}  // namespace brickyard::mapping
