#pragma once
// Scores perception against the simulator's ground truth, framework-free; sim.perception_scorer
// is its adapter, bench/eval_perception uses the geometry.
//  - Wall: the estimate's d_w against where the body's y axis (x = 0, z = 0) meets the wall.
//  - Obstacles: each is matched to a pylon within match_radius (body-frame xy); unmatched ones
//    are false obstacles.
//  - Pylon range: per pylon, over the frames that see it ahead between min_range and
//    max_range, the largest distance from which every nearer frame detected it.
#include "track.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <deque>
#include <vector>

namespace brickyard::sim {

// The body-frame y at which the body's y axis (x = 0, z = 0) meets the wall on `side` (-1 right,
// +1 left); NaN where that side has no wall.
double wall_y_in_body(const Track& track, const Eigen::Isometry3d& world_from_body, int side);
// A pylon's centre (half its height up) in the body frame.
Eigen::Vector3d pylon_in_body(const Track& track, const Eigen::Isometry3d& world_from_body, std::size_t pylon);

struct PerceptionScoreParams {
  int wall_side = -1;
  double match_radius = 1.0;          // m
  double min_range = 10, max_range = 200;  // m ahead: the pylon frames that count for its range
};

class PerceptionScore {
 public:
  PerceptionScore(const Track& track, PerceptionScoreParams p) : track_(track), p_(p) {}
  void truth(std::int64_t stamp_ns, const Eigen::Isometry3d& world_from_body);
  // Each returns false when no truth is at or before the stamp (the sample is not scored).
  bool wall(std::int64_t stamp_ns, double distance, bool valid);
  bool obstacles(std::int64_t stamp_ns, const std::vector<Eigen::Vector2d>& xy);

  const std::vector<double>& wall_errors() const { return wall_errors_; }
  std::size_t wall_frames() const { return wall_frames_; }
  std::size_t obstacle_frames() const { return obstacle_frames_; }
  std::size_t false_obstacles() const { return false_obstacles_; }
  // Per pylon: the reliable detection range (0: never reliable, NaN: never in view).
  std::vector<double> pylon_ranges() const;
  static double percentile(std::vector<double> v, double q);

 private:
  const Eigen::Isometry3d* pose_at(std::int64_t stamp_ns) const;
  const Track& track_;
  PerceptionScoreParams p_;
  std::deque<std::pair<std::int64_t, Eigen::Isometry3d>> truth_;
  std::vector<double> wall_errors_;
  std::size_t wall_frames_ = 0, obstacle_frames_ = 0, false_obstacles_ = 0;
  std::vector<std::vector<std::pair<double, bool>>> pylon_seen_;  // per pylon: (distance, detected)
};

}  // namespace brickyard::sim
