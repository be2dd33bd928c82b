#pragma once
// The paper's wall extraction (§III-B), framework-free: the longest cluster on one side of the
// car is the wall; its points, projected to the vehicle's z = 0 plane, are fitted by least squares
// with a polynomial y(x).
//
// Projection: on a banked turn the car is rolled against a wall that stands vertical in the
// world, so in the vehicle frame the wall leans: y moves by z·tan(roll) up its face (≈0.16 m per
// metre at 9.2°). Dropping z would fit the wall at the mean height of its returns, not at z = 0;
// the fit therefore carries one more unknown, the lean k, and fits y = p(x) + k·z. The polynomial
// p is the wall at z = 0. (lean: false fits p alone, the plain projection.)
#include "points.hpp"

#include <vector>

namespace brickyard::perception {

struct WallParams {
  int side = -1;             // -1 right (y < 0), +1 left
  int degree = 2;            // of y(x)
  bool lean = true;          // fit the lean y = p(x) + k z (see above)
  double lookahead = 10.0;   // m: heading and curvature are taken at x = lookahead
  int min_points = 30;       // fewer: not valid
  double min_length = 5.0;   // m of x extent; shorter: not valid
  double max_residual = 0.3; // m RMS; above: not valid
};

struct WallFit {
  std::vector<double> coefficients;  // c0 + c1 x + ..., at z = 0
  double lean = 0;                   // dy/dz
  double distance = 0;               // y(0)
  double heading = 0;                // atan(y'(lookahead)), rad
  double curvature = 0;              // y'' / (1 + y'^2)^1.5 at the look-ahead, 1/m
  double residual = 0;               // RMS, m
  double x_min = 0, x_max = 0;       // extent of the fitted points
  int cluster = -1;                  // index into the clusters; -1: no candidate
  std::size_t points = 0;
  bool valid = false;
};

// The index of the longest (x extent) cluster whose centroid lies on the side; -1 if none.
int longest_cluster_on_side(const Points& points, const std::vector<std::vector<int>>& clusters, int side);

// Fits the wall to the chosen cluster (see WallParams for validity).
WallFit fit_wall(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p);

// y of a polynomial and its first two derivatives at x.
double poly_value(const std::vector<double>& c, double x, int derivative = 0);

}  // namespace brickyard::perception
