#pragma once
// Obstacle extraction, framework-free: the clusters inside the drivable corridor that are not
// wall. A cluster the wall fit took as part of the wall (WallFit::members) is wall. The corridor
// is |y| <= max_lateral in the vehicle frame, cut by each fitted wall: a cluster with any point
// within wall_margin of a wall (or beyond it) is wall or outside the track. A cluster longer than max_length is structure (a wall the fit did not see), not an
// obstacle. A cluster with less than min_height of z extent is a single scan row's streak: the
// foot or the top of a wall far round a turn; anything that stands on the track is cut by two
// rows before it is near (a pylon from 100 m, see docs/results-perception.md). A cluster of four
// or more points lying flat (thinner than flat_thickness across its best-fit plane, that plane
// within flat_tilt_deg of the car's) is ground the filter missed: a road crease on a steep bank.
#include "points.hpp"
#include "wall_fit.hpp"

#include <vector>

namespace brickyard::perception {

struct ObstacleParams {
  double max_lateral = 15.0;  // m either side of the car
  double max_range = 200.0;   // m ahead
  double max_behind = 50.0;   // m behind: what the planner needs; far behind, the rear LiDARs graze
                              // the wall and its stripes are the hardest to tell from obstacles
  double wall_margin = 0.5;   // m: this close to a fitted wall is wall
  double max_length = 8.0;    // m of extent in x or y
  double min_height = 0.1;    // m of extent in z: a single scan row's streak has none
  double flat_thickness = 0.05;  // m: a cluster thinner than this (RMS across its best plane)...
  double flat_tilt_deg = 40;     // ...whose plane lies within this of the car's is ground
  int min_points = 2;
};

struct Obstacle {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  Eigen::Vector3f size = Eigen::Vector3f::Zero();  // axis-aligned extent
  std::size_t points = 0;
};

// `walls`: the valid fits (others are ignored); each wall's side (-1 right, +1 left) says which
// side of its line is outside the track.
std::vector<Obstacle> find_obstacles(const Points& points, const std::vector<std::vector<int>>& clusters,
                                     const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p);

}  // namespace brickyard::perception
