#pragma once
// The paper's wall extraction (§III-B), framework-free: the longest cluster on one side of the
// car is the wall; its points, projected to the vehicle's z = 0 plane, are fitted by least squares
// with a polynomial y(x).
//
// Growing: far ahead, a LiDAR meets a wall at a grazing angle and its columns land metres apart
// along it, each a separate cluster (a thin vertical stripe that would pass for a pylon). So the
// wall is grown from the longest cluster, end by end: a cluster (on either side: far round a turn
// the wall crosses the car's axis) that starts at most join_gap beyond an end, with nine in ten
// of the points of its first 2 m within join_margin + join_slope * (distance past the end) of
// the wall's local fit (its last 30 m, extrapolated), is wall too. The polynomial is then fitted to the wall's points
// within fit_range of the car, where it has to be right.
//
// Projection: on a banked turn the car is rolled against a wall that stands vertical in the
// world, so in the vehicle frame the wall leans: y moves by z·tan(roll) up its face (≈0.16 m per
// metre at 9.2°). Dropping z would fit the wall at the mean height of its returns, not at z = 0;
// the fit therefore carries one more unknown, the lean k, and fits y = p(x) + k·z. The polynomial
// p is the wall at z = 0. (lean: false fits p alone, the plain projection.)
#include "points.hpp"
#include "math/polynomial.hpp"

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
  double join_gap = 30.0;    // m beyond an end of the wall where a cluster may continue it
  double join_margin = 0.3;  // m from the wall's extrapolated local fit, at the wall's end...
  double join_slope = 0.05;  // ...plus this much per metre past it
  double fit_range = 20.0;   // m: the polynomial is fitted to the wall's points with |x| <= this...
  double fit_behind = 20.0;  // m: ...and x >= -fit_behind: a wall bending round a turn is fitted
                             // where the car goes, not where it has been
};

struct WallFit {
  std::vector<double> coefficients;  // c0 + c1 x + ..., at z = 0
  double lean = 0;                   // dy/dz
  double distance = 0;               // y(0)
  double heading = 0;                // atan(y'(lookahead)), rad
  double curvature = 0;              // y'' / (1 + y'^2)^1.5 at the look-ahead, 1/m
  double residual = 0;               // RMS, m
  double x_min = 0, x_max = 0;       // extent of the fitted points
  int cluster = -1;                  // the longest cluster (index into the clusters); -1: none
  std::vector<int> members;          // every cluster found to be this wall, the longest first
  std::size_t points = 0;            // fitted
  bool valid = false;
};

// The index of the longest (x extent) cluster on the side (-1 right, +1 left) where it passes the
// car: judged by its points within `near` of x = 0, or its point nearest to x = 0; of those, one
// with a point in the fit's window x in [-behind, near] if any has; -1 if none.
int longest_cluster_on_side(const Points& points, const std::vector<std::vector<int>>& clusters, int side, float near, float behind);

// Fits the wall to the chosen cluster (see WallParams for validity).
WallFit fit_wall(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p);

using math::poly_value;  // y of a polynomial, or a derivative, at x

}  // namespace brickyard::perception
