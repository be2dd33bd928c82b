#pragma once
// vehicle_interface.raptor_dbw's ports (plugin.cpp): the stack's commands, and for the stop along
// the last path its path, estimate, IMU and the track's map; the reports, race control and the
// bus's frames out. Plugin-side (SDK).
#include <brickyard/msgs/CanFrames.h>
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/RaceControl.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/VehicleStatus.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

namespace brickyard::vehicle_interface {

struct Ports {
  Input<msgs::ControlCommand> command;
  Input<msgs::Path> path;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::Imu> imu;
  Input<msgs::TrackMap> map;
  Output<msgs::WheelSpeeds> speeds;
  Output<msgs::VehicleStatus> status;
  Output<msgs::RaceControl> race_control;
  Output<msgs::CanFrames> frames;
};

inline PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("command", &Ports::command).doc("steer, throttle, brake: driven until command_timeout_s old, then a stop").depth(16);
  b.input("path", &Ports::path).doc("the planner's path: the stop steers along the last one (unwired: the wheel held)").optional().depth(2);
  b.input("estimate", &Ports::estimate).doc("the car's pose: where the stop along the path starts from").optional().depth(8);
  b.input("imu", &Ports::imu).doc("the IMU (its own process's, to outlive the stack): the stop's yaw rate (unwired: the car's model)").optional().depth(16);
  b.input("map", &Ports::map).doc("the track: the stop's line keeps room to its edges (unwired: the path as it is)").optional().depth(1);
  b.output("speeds", &Ports::speeds).doc("the four wheel speeds of wheel_speed_report, m/s, stamped at receipt");
  b.output("status", &Ports::status).doc("the reports (steering, brakes, gear, rpm, diagnostics) and the interface's state, at status_hz");
  b.output("frames", &Ports::frames).doc("the frames written and read in each step, raw and decoded by the DBC (parameter frames): the bus in a recording");
  b.output("race_control", &Ports::race_control).doc("race control's flags, target speed, lap and heartbeat: on each frame, at status_hz");
  return b;
}

}  // namespace brickyard::vehicle_interface
