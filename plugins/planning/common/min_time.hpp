#pragma once
// The minimum-time refinement of a racing line, framework-free: from offsets α along the
// reference line's left normals (the minimum-curvature line's, min_curvature.hpp), lower the lap
// time T(α) — Menger curvature of the points, the ggv + drag profile of speed_profile.hpp —
// inside the same box, with the bending energy Σ κ² ds kept within a slack of the start's.
//
// Each step is the box-constrained QP  min gᵀd + ½ dᵀ(ρ S + 2ν JᵀJ) d + 2ν (Jᵀr)ᵀd,
// lo − α ≤ d ≤ hi − α: g = dT/dα (reverse accumulation through the profile's passes), S = I +
// (ℓ/h)⁴ D₂ᵀD₂ a smoothing metric (D₂ second differences, h the spacing, ℓ `smoothing`), so a
// step is smooth over about ℓ and bends the line where that buys time, not point by point; r, J
// the residuals κ√ds whose squares sum to Σ κ² ds and their Jacobian (a Gauss-Newton model, its
// price ν raised only when a step would break the slack). A step is kept when the true lap time
// goes down and the true Σ κ² ds stays within the slack; otherwise ρ grows (a shorter step).
// docs/planning.md has the comparison with TUM's lines.
#include "min_curvature.hpp"
#include "speed_profile.hpp"

#include <vector>

namespace brickyard::planning {

struct MinTimeParams {
  double margin = 1.5;             // m kept from each edge: the same box as MinCurvatureParams'
  double curvature_slack = 0.003;  // Σ κ² ds may end at most this fraction above the start's
  double smoothing = 30;           // m: ℓ, the length a step is smooth over
  int max_iterations = 40;         // steps tried (each one QP)
  double tolerance = 1e-4;         // s: stop when a kept step gains less
};

struct MinTimeResult {
  std::vector<double> x, y;             // the line
  std::vector<double> offset;           // from the input line, m, left positive
  double start_time = 0, time = 0;      // lap_time() of the start and of the result, s
  double start_energy = 0, energy = 0;  // summed_squared_curvature() of both, 1/m
  int iterations = 0;                   // steps tried
  int accepted = 0;                     // steps kept
  int active_set_rounds = 0;            // over all QPs
};

// start: one offset per point (clamped into the box), e.g. MinCurvatureResult::offset; empty:
// the input line. Deterministic; never returns a slower line than the start (time ≤ start_time).
// Throws std::invalid_argument for a malformed line, start or parameters.
MinTimeResult min_time_refine(const ClosedLine& line, const std::vector<double>& start, const VehicleLimits& limits,
                              const MinTimeParams& p = {});

// The lap time of a closed line under the limits: Menger (three-point) curvature of each point,
// the closed ggv + drag profile; the measure the comparison with TUM's lines uses, s.
double lap_time(const std::vector<double>& x, const std::vector<double>& y, const VehicleLimits& limits);

}  // namespace brickyard::planning
