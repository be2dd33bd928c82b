#pragma once
// Simulated LiDAR frames of IMS with their ground truth, for eval_perception and bench_perception:
// the car on the track at (s, d), its three Luminar Hydras (AV-21 mounts, as configs/
// sim_truth_lap.json) cast against the banked road, both walls and the pylons; every point
// carries the surface it hit.
#include "sim/common/lidar.hpp"
#include "perception/common/points.hpp"

#include <memory>
#include <string>
#include <vector>

namespace brickyard::scenes {

using perception::Points;

struct Frame {
  Points points;                        // vehicle frame, all three sensors
  std::vector<sim::Surface> surface;    // per point
  // Each sensor's returns as it gives them (sensor frame, with intensities) and its mount.
  struct Scan {
    Eigen::Isometry3d vehicle_from_sensor;
    std::vector<float> x, y, z, intensity;
  };
  std::vector<Scan> scans;
  Eigen::Isometry3d world_from_body;
  double s = 0, d = 0;
};

struct ImsOptions {
  double bank_deg = 9.2;             // turns (curvature mode)
  bool inner_wall = false;           // 2 m beyond the inside edge (the outer wall, at the edge, always)
  std::vector<sim::Pylon> pylons;    // s, d, radius, height
};

class Ims {
 public:
  // `data_dir`: the folder holding tracks/IMS.csv.
  Ims(const std::string& data_dir, const ImsOptions& o);
  const sim::Track& track() const { return *track_; }
  // A straight and a banked turn: s of a point with bank 0 (resp. the full bank) for 300 m ahead.
  double straight_s() const { return straight_s_; }
  double turn_s() const { return turn_s_; }

  // The car resting on the road at (s, d), heading along the centre line.
  Eigen::Isometry3d pose(double s, double d) const;
  Frame frame(double s, double d, std::uint64_t seed) const;

  // Ground truth of the wall detector: the body-frame y at which the body's y axis (x = 0,
  // z = 0) meets the wall on `side` (-1 right, +1 left).
  double wall_y(const Eigen::Isometry3d& world_from_body, int side) const;
  // A pylon's centre (half its height up) in the body frame.
  Eigen::Vector3d pylon_in_body(const Eigen::Isometry3d& world_from_body, std::size_t pylon) const;

 private:
  std::unique_ptr<sim::Track> track_;
  std::vector<std::unique_ptr<sim::LidarCaster>> lidars_;
  double straight_s_ = 0, turn_s_ = 0;
};

}  // namespace brickyard::scenes
