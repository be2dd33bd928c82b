#pragma once
// Scan-to-map registration by voxelized GICP (Koide, Yokozuka, Oishi and Banno, ICRA 2021): the
// pose T that brings a scan's points, each with its covariance, onto a VoxelMap, minimizing
//   sum_i  N_v (mu_v - T a_i)^T (Sigma_v + R C_i R^T)^-1 (mu_v - T a_i)
// over each point's voxel v (N_v points, mean mu_v, mean covariance Sigma_v), by Gauss-Newton
// with Levenberg-Marquardt damping on SE(3). Steps are (omega, v): a turn omega about the scan's
// own origin in the map (the car) and a move v of it, both in the map's axes. Framework-free;
// one thread.
#include "voxel_map.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace brickyard::mapping {

struct RegistrationParams {
  int max_iterations = 64;
  double translation_eps = 1e-4;   // m: converged when a step moves less than this
  double rotation_eps = 1e-5;      // rad, and turns less than this
  // On: each point is matched to its own voxel and the 6 that share a face with it (VGICP's
  // DIRECT7), which pulls from farther; off: its own voxel alone (DIRECT1), a seventh of the cost.
  bool face_neighbours = true;
  // The scan's terms are multiplied by this. GICP takes every point's error as independent, so
  // its information grows with the number of points, far past what a scan knows (neighbouring
  // points share the surface's sampling and the pose's error): beside a prior, the weight says
  // how many points' worth a scan is (ScanMapperParams::points_worth).
  double weight = 1.0;
  // Every stride-th point of the scan is used (its terms weighted by stride, so the prior keeps
  // its share).
  int stride = 1;
  // Coarse to fine (the register_scan of several maps): the stages before the last use every
  // coarse_stride-th point. A coarse voxel's mean stands for a metre of surface; the coarse
  // stage brings the guess near, the last one is accurate with every point.
  int coarse_stride = 4;
};

// A prior on the pose (another estimate of it, such as the fusion's): its mean and its
// information (inverse covariance) over the step's coordinates, rotation omega then translation
// v (the car's turn and position), both in the map's axes. Its term (r^T Lambda r, r = (log(R R_p^T), t - t_p)) is added to the
// objective: what the scans do not tell (the motion along a smooth straight between smooth walls)
// the prior does.
struct PosePrior {
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

struct RegistrationResult {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  // map from scan
  int iterations = 0;
  bool converged = false;
  std::size_t matched = 0;  // source points with at least one voxel at the end
  double cost = 0;          // the objective at the end, per matched point
  // The Gauss-Newton system's matrix at the end (prior included), over (omega, v): its inverse
  // is the pose's covariance (the car's turn and position), as far as the points' own
  // covariances are right and their errors independent.
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();
  // The objective's gradient there (prior included), over the same coordinates: not quite zero
  // where the steps stopped before the minimum.
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
};

// The prior's residual at T, r = (log(R R_p^T), t - t_p), over the step's coordinates.
Eigen::Matrix<double, 6, 1> prior_residual(const Eigen::Isometry3d& mean, const Eigen::Isometry3d& T);
// The step (omega, v) from T: a turn about T's position, then a move.
Eigen::Isometry3d moved_by(const Eigen::Matrix<double, 6, 1>& d, const Eigen::Isometry3d& T);

// Registers `scan` (scan frame, with its points' surfaces in the scan frame: point_surfaces)
// onto `map`, from `guess` (map from scan). Fewer than 6 matched points: not converged, the
// guess returned.
RegistrationResult register_scan(const Points& scan, const Surfaces& surfaces, const VoxelMap& map,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p = {},
                                 const PosePrior* prior = nullptr);

// Coarse to fine: the same scan registered on each map in turn (largest voxels first), each
// from the last one's result. Why: a voxel's mean stands for all its points, so coarse voxels
// reach far (a guess 0.4 m off) but bias the result by centimetres where a voxel holds the edge
// of a surface or two surfaces; fine voxels are accurate but only from near the answer (measured
// on a walled yard: 1 m voxels from 0.4 m off, 9 cm left; 0.25 m voxels from there, 1 mm).
// Not converged when the last stage did not converge.
RegistrationResult register_scan(const Points& scan, const Surfaces& surfaces, const std::vector<const VoxelMap*>& maps,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p = {},
                                 const PosePrior* prior = nullptr);

}  // namespace brickyard::mapping
