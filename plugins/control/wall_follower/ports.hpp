#pragma once
// control.wall_follower's ports (plugin.cpp): the walls, the car's motion, the manager's mode, and
// for the offset line the map, the estimate and the planner's path; the command and the wall
// followed. Plugin-side (SDK).
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

namespace brickyard::control {

struct Ports {
  Input<msgs::WallEstimate> wall, wall_left, wall_right;
  Input<msgs::WheelSpeeds> wheels;
  Input<msgs::Imu> imu;
  Input<msgs::ModeStatus> mode;
  Input<msgs::TrackMap> map;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::Path> path;
  Output<msgs::ControlCommand> command;
  Output<msgs::WallEstimate> followed;
};

inline PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("wall", &Ports::wall)
      .doc("the wall detector's estimate of the wall on 'side' (law paper: required)").optional().depth(4).steps();
  b.input("wall_left", &Ports::wall_left).doc("offset_line: the left wall's estimate").optional().depth(4).steps();
  b.input("wall_right", &Ports::wall_right).doc("offset_line: the right wall's estimate").optional().depth(4).steps();
  b.input("wheels", &Ports::wheels).doc("speed, independent of GNSS");
  b.input("imu", &Ports::imu).doc("offset_line: the yaw rate that carries the car along the line between wall frames (optional)")
      .optional().depth(32).steps();
  b.input("mode", &Ports::mode).doc("the system manager's mode: taking over starts the speed policy (optional)")
      .optional().depth(8);
  b.input("map", &Ports::map).doc("offset_line: the track, whose edge on the wall's side gives the wall's shape ahead (optional)")
      .optional().depth(1);
  b.input("estimate", &Ports::estimate)
      .doc("offset_line with a map: the pose that places the map's edge round the car (optional)")
      .optional().depth(8);
  b.input("path", &Ports::path)
      .doc("offset_line with a map: the planner's path; where the wall and the map agree, the car follows it, "
           "placed by the wall (optional)")
      .optional().depth(2);
  b.output("command", &Ports::command).doc("steer and pedals, source \"wall_follower\"");
  b.output("followed", &Ports::followed)
      .doc("offset_line: the wall followed, every wall frame (valid while there is a line to follow, a held one included)");
  return b;
}

}  // namespace brickyard::control
