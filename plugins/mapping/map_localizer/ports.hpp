#pragma once
// mapping.map_localizer's ports (plugin.cpp): the ground filter's frames and the estimate in, the
// pose found out. Plugin-side (SDK).
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

namespace brickyard::mapping {

struct LocalizerPorts {
  Input<msgs::PointCloud> points, ground;
  Input<msgs::LocalizationEstimate> estimate;
  Output<msgs::LocalizationEstimate> pose;
};

inline PortBinding<LocalizerPorts> localizer_ports() {
  PortBinding<LocalizerPorts> b;
  b.input("points", &LocalizerPorts::points).doc("the ground filter's vertical features, vehicle frame").depth(8);
  b.input("ground", &LocalizerPorts::ground).doc("the ground filter's ground, vehicle frame, the same frames").depth(8).steps();
  b.input("estimate", &LocalizerPorts::estimate).doc("the pose estimate (the fusion's): each frame's guess at its stamp").depth(64);
  b.output("pose", &LocalizerPorts::pose)
      .doc("the pose found on the map, stamped with the frame; covariance over (x, y, yaw); update_case 2: located, 0: not");
  return b;
}

}  // namespace brickyard::mapping
