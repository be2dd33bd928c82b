#pragma once
// Generalized ICP with point-to-point correspondences (Segal, Haehnel and Thrun, 2009), the
// algorithm of PCL's GeneralizedIterativeClosestPoint, beside the voxelized one of vgicp.hpp:
// each source point a_i matched to its nearest target point b_i within max_correspondence_m,
// then
//   sum_i (b_i - T a_i)^T (C_bi + R0 C_ai R0^T)^-1 (b_i - T a_i)
// minimized with the matches and the weights (R0: the rotation when they were found) held, by
// Gauss-Newton on SE(3); matched again from the result, until a round moves the pose less than
// the epsilons, or back to where an earlier round ended (matches that alternate). Its answer is
// a fixed point of that loop: where the matches found at T give T back. Why it is here: the
// voxel map is the car's registration (a scan against a map of millions of points, VGICP: one
// lookup per point); this one answers "the same as PCL's GICP?"
// on sparse scans where a voxel's mean is a poor stand-in for the points (cuICP's pair,
// docs/mapping.md), and serves scan-to-scan matching of small clouds. Framework-free; one
// thread; the nearest neighbours by a grid of max_correspondence_m cells.
#include "covariances.hpp"
#include "vgicp.hpp"

namespace brickyard::mapping {

struct PointRegistrationParams {
  double max_correspondence_m = 5;  // PCL's default (corr_dist_threshold_)
  int max_iterations = 64;          // rounds of matching
  int inner_iterations = 20;        // Gauss-Newton steps per round, the matches held
  double translation_eps = 1e-6;    // m: a round that moves the pose less (and turns it less) ends it
  double rotation_eps = 1e-6;       // rad
};

// `source` onto `target`, each with its points' surfaces (point_surfaces), from `guess` (target
// from source). Fewer than 6 matches: not converged, the guess returned. RegistrationResult's
// `iterations` counts rounds of matching; its hessian is the last round's system.
RegistrationResult register_points(const Points& source, const Surfaces& source_surfaces, const Points& target,
                                   const Surfaces& target_surfaces, const Eigen::Isometry3d& guess,
                                   const PointRegistrationParams& p = {});

}  // namespace brickyard::mapping
