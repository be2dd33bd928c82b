#pragma once
// The minimum-curvature racing line (paper §III-C, offline), framework-free: lateral offsets α_i
// along the reference line's left normals, within the track edges less a margin, minimising the
// summed squared curvature of the resulting closed line.
//
// Curvature is linear in α when the tangents are held: with arc-length spacing h, the curvature
// at point i is t_i × q''_i, q''_i = (q_{i+1} − 2 q_i + q_{i−1}) / h², q_j = p_j + α_j n_j. So
// κ = κ_ref + M α and the problem is the box-constrained least squares min |κ_ref + M α|²,
// l ≤ α ≤ u: a QP with a pentadiagonal (cyclic) Hessian, solved by an active set over a sparse
// LDLᵀ. Holding the tangents is an approximation; the line is re-sampled and the QP solved again
// from it until the offsets stop moving ("iterated to convergence").
#include <vector>

namespace brickyard::planning {

struct ClosedLine {
  std::vector<double> x, y;                    // points, closed (the last joins the first)
  std::vector<double> width_left, width_right; // m to each edge from the point, along its normal
};

struct MinCurvatureParams {
  double margin = 1.5;      // m kept from each edge: half the car's width (0.97) and a margin
  int max_iterations = 32;  // re-linearisations
  double tolerance = 0.01;  // m: stop when no offset moves more than this
};

struct MinCurvatureResult {
  std::vector<double> x, y;     // the line
  std::vector<double> offset;   // from the input line, m, left positive
  int iterations = 0;
  int active_set_rounds = 0;    // over all iterations
};

MinCurvatureResult min_curvature_line(const ClosedLine& line, const MinCurvatureParams& p = {});

// Σ κ_i² · ds_i of a closed line (three-point curvature), the quantity minimised; 1/m.
double summed_squared_curvature(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace brickyard::planning
