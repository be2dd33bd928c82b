#pragma once
// Adapter shared by the simulator plugins: the TrackWorld message to and from sim::WorldSpec,
// and the vehicle pose as an isometry. Header-only, used by plugin.cpp files only.
#include <brickyard/msgs/TrackWorld.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/context.hpp>

#include <Eigen/Geometry>

#include "sim/common/track.hpp"
#include "map_msg.hpp"
#include "newest.hpp"

namespace brickyard::sim {

// The other cars a simulator node takes (issue 46): inputs other0 to other3, each another
// sim.vehicle's truth; the same count for the LiDARs, the referee and the tracking scorer.
inline constexpr std::size_t kOtherCars = 4;

inline msgs::TrackWorld to_message(const Track& t) {
  const WorldSpec& w = t.spec();
  msgs::TrackWorld m;
  plugins::write_geometry(m, w);
  m.wall_left(w.walls.left);
  m.wall_left_offset_m(w.walls.left_offset);
  m.wall_right(w.walls.right);
  m.wall_right_offset_m(w.walls.right_offset);
  m.wall_height_m(w.walls.height);
  for (const auto& p : w.pylons) {
    msgs::Pylon q;
    q.s(p.s); q.d(p.d); q.x(p.x); q.y(p.y); q.z(p.z); q.radius(p.radius); q.height(p.height);
    m.pylons().push_back(q);
  }
  return m;
}

inline WorldSpec from_message(const msgs::TrackWorld& m) {
  WorldSpec w;
  plugins::read_geometry(m, w);
  w.walls.left = m.wall_left();
  w.walls.left_offset = m.wall_left_offset_m();
  w.walls.right = m.wall_right();
  w.walls.right_offset = m.wall_right_offset_m();
  w.walls.height = m.wall_height_m();
  for (const auto& q : m.pylons()) {
    Pylon p;
    p.s = q.s(); p.d = q.d(); p.radius = q.radius(); p.height = q.height();
    w.pylons.push_back(p);
  }
  return w;
}

// world_from_body of a VehicleState (base_link): yaw, then pitch, then roll.
inline Eigen::Isometry3d body_pose(const msgs::VehicleState& s) {
  return Eigen::Translation3d(s.x(), s.y(), s.z()) * Eigen::AngleAxisd(s.yaw(), Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(s.pitch(), Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(s.roll(), Eigen::Vector3d::UnitX());
}

using plugins::newest;

inline std::int64_t stamp(const msgs::VehicleState& s) { return s.header().stamp_ns(); }

}  // namespace brickyard::sim
