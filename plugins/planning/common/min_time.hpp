#pragma once
// The minimum-time refinement of a racing line, framework-free: from offsets α along the
// reference line's left normals (the minimum-curvature line's, min_curvature.hpp), lower the lap
// time inside the same box, with the bending energy Σ κ² ds kept within a slack of the start's.
// Two measures of the lap time, both the ggv + drag profile of speed_profile.hpp: T_p with the
// Menger curvature of each point (the comparison's measure), and T_a with that curvature averaged
// over `averaged_over` m by track::signed_curvature (as brickyard-plan --profile writes the line and
// the driving stack sees it). The objective is T = T_p + T_a (T_p alone with averaged_over 0).
//
// Each step is the box-constrained QP  min gᵀd + ½ dᵀ(ρ S + 2ν JᵀJ) d + 2ν (Jᵀr)ᵀd,
// lo − α ≤ d ≤ hi − α: g = dT/dα (reverse accumulation through the profile's passes; T_a's
// derivatives by the raw curvatures through the average's adjoint, the same average), S = I +
// (ℓ/h)⁴ D₂ᵀD₂ a smoothing metric (D₂ second differences, h the spacing, ℓ `smoothing`), so a
// step is smooth over about ℓ and bends the line where that buys time, not point by point; r, J
// the residuals κ√ds whose squares sum to Σ κ² ds and their Jacobian (a Gauss-Newton model, its
// price ν raised only when a step would break the slack). A step is kept when the true T goes
// down, neither T_p nor T_a goes up and the true Σ κ² ds stays within the slack; otherwise ρ
// grows (a shorter step). docs/planning.md has the comparison with TUM's lines.
#include "min_curvature.hpp"
#include "motion/speed_profile.hpp"

#include <vector>

namespace brickyard::planning {

using motion::VehicleLimits;
using motion::closed_lap_time_gradient;
using motion::profile_time;
using motion::speed_profile;

struct MinTimeParams {
  double margin = 1.5;             // m kept from each edge: the same box as MinCurvatureParams'
  double curvature_slack = 0.003;  // Σ κ² ds may end at most this fraction above the start's
  double smoothing = 30;           // m: ℓ, the length a step is smooth over
  double averaged_over = 30;       // m: T_a's curvature average (lap_profile's average_m); 0: T_p alone
  int max_iterations = 80;         // steps tried (each one QP)
  double tolerance = 1e-4;         // s: stop when a kept step gains less (in T_p + T_a)
};

struct MinTimeResult {
  std::vector<double> x, y;             // the line
  std::vector<double> offset;           // from the input line, m, left positive
  double start_time = 0, time = 0;      // T_p, lap_time(), of the start and of the result, s
  double start_averaged_time = 0;       // T_a, lap_time(…, averaged_over), of the start, s (0: averaged_over 0)
  double averaged_time = 0;             // and of the result
  double start_energy = 0, energy = 0;  // summed_squared_curvature() of both, 1/m
  int iterations = 0;                   // steps tried
  int accepted = 0;                     // steps kept
  int active_set_rounds = 0;            // over all QPs
};

// start: one offset per point (clamped into the box), e.g. MinCurvatureResult::offset; empty:
// the input line. Deterministic; never returns a line slower than the start under either measure
// (time ≤ start_time, averaged_time ≤ start_averaged_time).
// Throws std::invalid_argument for a malformed line, start or parameters.
MinTimeResult min_time_refine(const ClosedLine& line, const std::vector<double>& start, const VehicleLimits& limits,
                              const MinTimeParams& p = {});

// A closed line's steps (ds[i] from point i to the next), curvatures, speed profile and lap time.
struct LapProfile {
  std::vector<double> ds, kappa, v;
  double time = 0;  // s
};

// The closed line's lap under the limits (the closed ggv + drag profile) with each point's
// curvature the Menger (three-point) curvature of it and its neighbours (average_m 0: the
// measure of the comparison with TUM's lines), or that averaged over average_m of line by
// track::signed_curvature (30 m: as `brickyard-plan line --profile` writes it and the driving
// stack sees it). Throws std::invalid_argument for fewer than 3 points or x, y of unequal size.
LapProfile lap_profile(const std::vector<double>& x, const std::vector<double>& y, const VehicleLimits& limits,
                       double average_m = 0);

// lap_profile(x, y, limits, average_m).time, s.
double lap_time(const std::vector<double>& x, const std::vector<double>& y, const VehicleLimits& limits, double average_m = 0);

}  // namespace brickyard::planning
