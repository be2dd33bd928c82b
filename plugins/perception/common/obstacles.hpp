#pragma once
// Obstacle extraction, framework-free: the clusters inside the drivable corridor that are not
// wall.
//  - Wall: a cluster the wall fit took as part of the wall (WallFit::members), or with any point
//    within wall_margin of a fitted wall or beyond it (outside the track) — where the wall is
//    known (up to wall_reach past the ends of its points); further on, where its line is
//    extrapolated, only up to wall_depth beyond it (something far beyond a guessed wall line
//    says the guess is wrong there: the LiDAR does not see through walls).
//  - One object: clusters whose xy footprints overlap (within stack_gap). Far off, the rows a
//    pylon is cut by land further apart than the clustering tolerance: one-row streaks stacked
//    at one place.
//  - Corridor: up to corridor_width inward of the first fitted wall, which is known from its
//    points far round a turn; with no wall fitted, |y| <= max_lateral. From max_behind behind
//    to max_range ahead.
//  - Not obstacles: longer than max_length (structure: a wall the fit did not see); less than
//    min_height of z extent (a single row's streak: the foot or top of a wall far round a turn;
//    what stands on the track is cut by two rows, a pylon from 160 m on a straight, see
//    docs/results-perception.md); four or more points lying flat (thinner than flat_thickness
//    across their best-fit plane, that plane within flat_tilt_deg of the car's: ground the filter
//    missed, a road crease on a steep bank).
#include "points.hpp"
#include "wall_fit.hpp"

#include <limits>
#include <vector>

namespace brickyard::perception {

struct ObstacleParams {
  double max_lateral = 15.0;     // m either side of the car, when no wall is fitted
  double corridor_width = 20.0;  // m inward from a fitted wall (the track and a margin)
  double max_range = 200.0;      // m ahead
  double max_behind = 15.0;      // m behind: what the planner needs (a thing beside the car, and
                                 // its length and clearance past it). Further behind, the rear
                                 // LiDARs graze the wall, the fit (made ahead) does not reach it,
                                 // and round a hairpin its stripes stood 1 m inside the edge
  double wall_margin = 0.5;      // m: this close to a fitted wall is wall
  double wall_reach = 30.0;      // m past the ends of what a fitted wall is known from (its points,
                                 // or the polynomial's extent) that all that lies beyond it is wall.
                                 // Further on its line is a guess, and only points within
                                 // wall_depth beyond it are wall: a wall extrapolated straight 180 m
                                 // along a bending straight put a pylon on the track "beyond" it
                                 // (Spielberg at 77 m/s: first reported at 103 m, not 186 m, and
                                 // too late to go round)
  double wall_depth = 1.0;       // m beyond a guessed wall line that is still wall (2 m hid the
                                 // Spielberg pylon: the guess ran 1 to 2 m inside the true wall)
  double max_length = 8.0;       // m of extent in x or y
  double min_height = 0.1;       // m of extent in z: a single scan row's streak has none
  double flat_thickness = 0.05;  // m: thinner than this (RMS across the best plane)...
  double flat_tilt_deg = 40;     // ...with that plane within this of the car's: ground
  double stack_gap = 0.3;        // m: clusters whose footprints come this close are one object
  int min_points = 2;
};

struct Obstacle {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  Eigen::Vector3f size = Eigen::Vector3f::Zero();  // axis-aligned extent
  std::size_t points = 0;
  // Its footprint: the convex hull of its points in the xy plane, counter-clockwise. A car seen at
  // a slant is an L of two faces; its extent along any direction (the track's, where it is) is
  // the hull's, where a box along the car's axes would be inflated by the slant (car_parts.hpp).
  std::vector<Eigen::Vector2f> outline;
  // The turn of the rectangle that fits its points best (rad, [0, pi/2): a rectangle's sides are
  // the same turned a quarter): most of them close to one of its sides, the back and side of a car
  // seen at a slant included, where the outline alone cannot tell an L from a triangle. NaN: too
  // few points or too small to say.
  float box_yaw = std::numeric_limits<float>::quiet_NaN();
};

// box_yaw's fit (Obstacle): over turns a degree apart then a tenth, the one whose rectangle about
// the points has them closest to its sides (each point's distance to the nearest side, scored
// 1 / max(distance, 1 cm), summed).
float fitted_box_yaw(const Points& points, const std::vector<int>& members);

// The convex hull (counter-clockwise, no three points in line) of the points' xy.
std::vector<Eigen::Vector2f> footprint_hull(const Points& points, const std::vector<int>& members);

// `walls`: the valid fits (others are ignored); each wall's side (-1 right, +1 left) says which
// side of its line is outside the track.
std::vector<Obstacle> find_obstacles(const Points& points, const std::vector<std::vector<int>>& clusters,
                                     const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p);

}  // namespace brickyard::perception
