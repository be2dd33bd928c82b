#pragma once
// A spinning LiDAR measures its columns across its rotation while the car moves: at 80 m/s a
// 10 Hz sensor's window of 127 degrees spans 35 ms, 2.8 m of travel. Each point moved into the
// vehicle frame at the frame's stamp, the car taken to drive a circular arc at its speed and yaw
// rate over the frame (docs/algorithms.md, "Motion within a frame"). Framework-free.
#include "frame_set.hpp"
#include "points.hpp"

#include <cstddef>

namespace brickyard::perception {

// The car's motion over a frame: forward speed (m/s) and yaw rate (rad/s), held constant.
struct PlanarMotion {
  double speed = 0, yaw_rate = 0;
};

// Where a point at p in the vehicle frame at t + dt lies in the vehicle frame at t: the frame at
// t + dt is turned by a = yaw_rate * dt and sits on the arc at speed * dt (its chord
// (sin a, 1 - cos a) * speed / yaw_rate). Series in a (|a| is a few hundredths of a radian
// within a frame; the terms left out are below a micrometre): no sin or cos per point.
inline Point moved_to_stamp(const Point& p, float dt, const PlanarMotion& m) {
  const float a = static_cast<float>(m.yaw_rate) * dt, a2 = a * a;
  const float c = 1 - a2 / 2, s = a * (1 - a2 / 6);
  const float run = static_cast<float>(m.speed) * dt;
  return {c * p.x() - s * p.y() + run * (1 - a2 / 6), s * p.x() + c * p.y() + run * a / 2, p.z()};
}

// As append_in_vehicle_frame, each point also moved to the frame's stamp: measured
// cloud_dt + time_offset[i] seconds after it (time_offset null: every point at cloud_dt).
inline void append_moved_to_stamp(const SensorPose& pose, const float* x, const float* y, const float* z,
                                  const float* time_offset, double cloud_dt, std::size_t n, const PlanarMotion& motion,
                                  Points& out) {
  append_in_vehicle_frame(pose, x, y, z, n, out, [&](std::size_t i, const Point& p) {
    return moved_to_stamp(p, static_cast<float>(cloud_dt) + (time_offset ? time_offset[i] : 0.0f), motion);
  });
}

}  // namespace brickyard::perception
