#pragma once
// The minimum-curvature racing line (paper §III-C, offline), framework-free: lateral offsets α_i
// along the reference line's left normals, within the track edges less a margin, minimising the
// bending energy Σ κ² ds of the resulting closed line.
//
// Gauss-Newton: with q_j = p_j + α_j n_j and central differences q', q'' at each point, the
// residual κ_i √ds_i (κ = q' × q'' / |q'|³, ds = |q'| h) is linearised at the current offsets, and
// the box-constrained least squares min |b + M α|², l ≤ α ≤ u — a QP with a pentadiagonal (cyclic)
// Hessian — is solved by a primal active set over a sparse LDLᵀ. The true objective decides the
// step (halved until it goes down); the loop ends when the offsets stop moving ("iterated to
// convergence"). docs/planning.md has the derivation and the comparison with TUM's lines.
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
  std::vector<double> start;  // initial offsets (clamped into the box); empty: the input line
};

struct MinCurvatureResult {
  std::vector<double> x, y;     // the line
  std::vector<double> offset;   // from the input line, m, left positive
  int iterations = 0;
  int active_set_rounds = 0;    // over all iterations
};

// The frame the offsets live in: unit left normals of the input line (central differences) and
// the box lo ≤ α ≤ hi, the edges less the margin (where the track is narrower than two margins,
// its middle). Throws std::invalid_argument, naming `who`, for fewer than 4 points or missing widths.
struct OffsetFrame {
  std::vector<double> nx, ny, lo, hi;
};
OffsetFrame offset_frame(const ClosedLine& line, double margin, const char* who);

MinCurvatureResult min_curvature_line(const ClosedLine& line, const MinCurvatureParams& p = {});

// Σ κ_i² · ds_i of a closed line (three-point curvature: track::menger_curvature), the quantity minimised; 1/m.
double summed_squared_curvature(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace brickyard::planning
