#pragma once
// Localization on a prior point map, framework-free: each LiDAR frame (vehicle frame) registered
// onto a map of the track made before (the PCD file mapping.scan_mapper writes), from a guess (the
// fusion's estimate at the frame's stamp). The map is not changed, so the pose found is a witness
// of its own: where the walls and the road fix it, the map says where the car is whatever GNSS
// says; along a smooth straight between smooth walls nothing in the frame does, and there the
// pose keeps the guess's coordinate with a spread of `unseen_sigma`: the covariance says the map
// cannot tell, never a confident pose the frame does not support.
#include "covariances.hpp"
#include "scan_mapper.hpp"
#include "vgicp.hpp"
#include "voxel_map.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cstddef>

namespace brickyard::mapping {

struct MapLocalizerParams {
  float coarse_voxel = 1.0f;  // m: the map registered on first, from the guess (reaches far)
  float fine_voxel = 0.25f;   // m: then on this one (accurate near the answer)
  // m: the frame thinned to one point (the mean) per voxel of this size. The cost goes with the
  // points left (at 0.8 m a third of 0.4 m's), but at 0.8 m within 100 m both receivers drifting
  // together on Spielberg's outer wall pulled the map's poses along, never caught, into the wall
  // (docs/map-localization.md); at 0.4 m caught in 3.7 s.
  float scan_voxel = 0.4f;
  // m from the car: farther points are left out. Where a wall is uniform (an oval's, alone), how
  // far along the car is shows only where a straight meets a turn: seen from farther, sooner.
  double max_range = 100.0;
  // How many independent points a frame counts as (its covariance; RegistrationParams::weight).
  // At 200 a clean lap's poses were off by up to 9 of their own sigmas (Spielberg, outer wall, a
  // map whose curves were banked, the road not yet levelled: NEES p99 88); at 20 every track's
  // sit within them, cautiously on maps of the race's own world (NEES p99 at most 0.5,
  // docs/results-gnss-faults.md).
  double points_worth = 20;
  double max_correction = 2.0;  // m: a pose farther from the guess in the plane is not taken
  double max_turn = 0.05;       // rad: nor one whose heading turned more
  std::size_t min_matched = 100;  // frame points matched to the map, at least
  double min_support = 30;        // a direction with less surface facing it is unseen (unseen_directions)
  double unseen_sigma = 100;      // m: the spread reported along an unseen direction
  // m: the least spread reported in any direction of the position. The registration's own
  // covariance says what the frame's noise allows, not what the map's making does (voxel means,
  // a wall mapped a few centimetres off): poses it said were sure to a centimetre or two were
  // off by several against the truth.
  double min_sigma = 0.1;
  // A weak prior at the guess (1 sigma): it keeps the solution where the frame tells nothing (the
  // registration would wander there by aliasing) and weighs nothing where the frame tells.
  // The frame's height is searched on the coarse map within this of the guess's first: a map's
  // height drifts over a mapping drive (its frames join on the ground's registration, with no
  // height from GNSS: 3.4 m over a lap of Spielberg, 10 m over one of Monza), so the height
  // carried from the last frame is metres off where the drive closed its loop. 0: the guess's.
  double height_search = 20.0;    // m
  double prior_sigma = 1.0;       // m
  double prior_sigma_turn = 0.1;  // rad
  // Surfaces within this of level (the road, in the map and in the frame) are made level: they
  // tell height, roll and pitch, never where the car is in the plane. A map's road can lie
  // otherwise than the frame's (a mapping drive's attitude drifts; a map made banked where the
  // race is flat rose about 17 % across the road in a bend of Spielberg), and a frame's road
  // matched onto it slides the pose metres sideways with a covariance sure to 0.15 m; where the plane position comes from the
  // walls alone, the covariance says what the walls tell. 0: the road kept as it is.
  double ground_tilt = 0.45;  // rad
  // Threads (1 or 2) that share the map's preparation at the start (its points' surfaces, its
  // two voxel maps): the same bits on either. A frame's surfaces stay on one: on two, 60 s of
  // Spielberg located every frame ran within the noise of one (the other core is busy with the
  // frame's other steps and the next frame's LiDARs; docs/map-localization.md).
  int threads = 2;
  CovarianceParams covariances;
  RegistrationParams registration{16, 5e-3, 5e-4, false};
};

// Why a frame was not located.
enum class LocateFailure { none, too_few_points, not_converged, too_few_matched, implausible, singular };  // singular last
const char* failure_name(LocateFailure f);

struct Located {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // map from vehicle: registered, else the guess
  bool registered = false;
  LocateFailure failure = LocateFailure::none;
  // Over (rotation omega, translation v), map axes: the frame's information (the registration's
  // system less the weak prior) inverted, with unseen_sigma^2 along each unseen direction.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity();
  std::size_t matched = 0;
  int iterations = 0;
  int unseen = 0;           // directions of translation the frame could not tell
  double correction = 0;    // m: how far the pose is from the guess in the plane
};

class MapLocalizer {
 public:
  // `map`: the map's points (map frame), such as read_pcd returns.
  explicit MapLocalizer(const Points& map, MapLocalizerParams p = {});
  const MapLocalizerParams& params() const { return p_; }
  std::size_t map_points() const { return points_; }
  const VoxelMap& fine_map() const { return fine_; }

  // One frame (vehicle frame) located from `guess` (map from vehicle), its height searched first.
  Located locate(const Points& frame, Eigen::Isometry3d guess) const;

 private:
  // The height at which most of the frame's points (every 8th) fall in the coarse map's voxels,
  // searched in half-voxel steps within height_search of the guess's, the nearest first (ties:
  // the nearest), until a height most of them fall on has none better near it.
  double height_on_map(const Points& near, const Eigen::Isometry3d& guess) const;
  // The frame's surfaces (vehicle frame) with its road level in the map's frame, its attitude
  // that of `guess`.
  Surfaces frame_surfaces(const Points& near, const Eigen::Isometry3d& guess) const;
  // The frame's own answer: the registration's minimum leans toward the guess by the weak prior's
  // pull, most where the frame tells little (along a smooth wall), while the covariance reported
  // is the frame's alone: a pose so leaned follows an estimate that drifts, sure of itself (both
  // receivers drifting together on Monza, 12 s into the fault: the map's poses 3.3 m off, said
  // sure to 0.5 m; docs/map-localization.md). One Gauss-Newton step of the frame's terms alone,
  // from the minimum, takes the pull back out (`frame_information`: the system less the prior).
  Eigen::Isometry3d without_prior_pull(const RegistrationResult& r, const Eigen::Isometry3d& guess,
                                       const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>>& frame_information) const;
  // The weak prior's information (prior_sigma, prior_sigma_turn).
  Eigen::Matrix<double, 6, 6> weak_prior() const;
  // The weak prior, and a hold along the `unseen` directions (a projector).
  Eigen::Matrix<double, 6, 6> prior_information(const Eigen::Matrix3d& unseen) const;
  // The position's covariance with min_sigma's spread at least in every direction (its
  // eigenvalues floored: a floor on the diagonal alone leaves a diagonal direction sure).
  void floor_position_spread(Eigen::Matrix<double, 6, 6>& covariance) const;
  // Along unseen directions: the guess's translation and unseen_sigma's spread.
  void keep_guess_where_unseen(const Surfaces& surfaces, const Eigen::Isometry3d& guess, Located& out) const;

  MapLocalizerParams p_;
  VoxelMap coarse_, fine_;
  std::size_t points_ = 0;
};

}  // namespace brickyard::mapping
