#pragma once
// The three estimators' ports (plugin.cpp): one binding, their ports are the same. Plugin-side (SDK).
#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include <array>

namespace brickyard::estimation {

struct Ports {
  Input<msgs::Imu> imu;
  Input<msgs::WheelSpeeds> wheels;
  std::array<Input<msgs::GnssFix>, 2> gnss;
  Input<msgs::LocalizationEstimate> scan_pose;
  Output<msgs::LocalizationEstimate> estimate;
  Output<msgs::ModeStatus> mode;
};

inline PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("imu", &Ports::imu).doc("IMU: the yaw rate drives the prediction").depth(256).steps();
  b.input("wheels", &Ports::wheels).doc("wheel speeds: the rear axle's speed drives the prediction").depth(256);
  b.inputs("gnss", &Ports::gnss).doc("fixes of one receiver each: gnss0 the first, gnss1 the second (optional)")
      .required_first(1).depth(64);
  b.input("scan_pose", &Ports::scan_pose)
      .doc("a second estimate of the pose (the scan mapper's), taken while GNSS is degraded (optional)").optional();
  b.output("estimate", &Ports::estimate).doc("pose, covariance, the update case, delta per receiver, status");
  b.output("mode", &Ports::mode).doc("the localization manager's status, on change and at 10 Hz");
  return b;
}

}  // namespace brickyard::estimation
