#pragma once
// Obstacle extraction, framework-free: the clusters inside the drivable corridor that are not
// wall. The corridor is |y| <= max_lateral in the vehicle frame, cut by each fitted wall: a
// cluster with any point within wall_margin of a wall (or beyond it) is wall or outside the
// track. A cluster longer than max_length is structure (a wall the fit did not see), not an
// obstacle.
#include "points.hpp"
#include "wall_fit.hpp"

#include <vector>

namespace brickyard::perception {

struct ObstacleParams {
  double max_lateral = 15.0;  // m either side of the car
  double max_range = 200.0;   // m ahead or behind
  double wall_margin = 0.5;   // m: this close to a fitted wall is wall
  double max_length = 8.0;    // m of extent in x or y
  int min_points = 3;
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
