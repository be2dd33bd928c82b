#pragma once
// Curvature of a closed line, one definition for the whole project: the Menger (three-point)
// curvature, and its cyclic moving average. Framework-free.
#include "centre_line.hpp"

#include <vector>

namespace brickyard::track {

// Signed curvature (1/m, left turns positive) of the circle through a, b, c: 2 sin(angle) / chord.
// Points that coincide give 0. `sides` (when not null) gets |ab| + |bc|.
double menger_curvature(double ax, double ay, double bx, double by, double cx, double cy, double* sides = nullptr);

// Signed curvature per point, averaged over `smooth_m` of track: the Menger curvature of each
// point with its neighbours, then cyclic_average over curvature_window points each side.
std::vector<double> signed_curvature(const CenterLine& line, double smooth_m);

// The half width, in points, of signed_curvature's average: smooth_m / 2 in mean steps of the
// closed line, rounded (0 for smooth_m <= 0).
int curvature_window(const CenterLine& line, double smooth_m);

// The cyclic moving average of v over the 2·half + 1 points around each. A symmetric linear map,
// so it is its own adjoint: derivatives by the averaged values become derivatives by the raw
// ones through the same function.
std::vector<double> cyclic_average(const std::vector<double>& v, int half);

}  // namespace brickyard::track
