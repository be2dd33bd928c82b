#pragma once
// The paper's mapping (§III-C), framework-free: each LiDAR frame (vehicle frame) registered onto
// the map built so far from the pose estimate, with that estimate as a prior, and added to the
// map on the pose found when the car has moved far enough since the last frame added. The pose
// found is a second estimate of the car's pose: across the track and in heading the walls and
// the road fix it; along a smooth straight between smooth walls nothing in the scan does, and
// the prior (the estimate's own covariance) holds it there, so its covariance says so.
#include "covariances.hpp"
#include "gravity_tilt.hpp"
#include "vgicp.hpp"
#include "voxel_map.hpp"

#include <Eigen/Geometry>

#include <cmath>

#include <optional>

namespace brickyard::mapping {

struct ScanMapperParams {
  float coarse_voxel = 1.0f;       // m: the map registered on first, from the guess (reaches far)
  float fine_voxel = 0.25f;        // m: then on this one (accurate near the answer); also the map written out
  double keyframe_distance = 2.0;  // m the car moves before a frame joins the map
  double max_range = 60.0;         // m from the car: farther points are left out (sparse, poor covariances)
  float scan_voxel = 0.4f;         // m: the frame thinned to one point (the mean) per voxel of this size first
  // How many independent points a registered scan counts as beside the prior (the scan's
  // terms weighted by points_worth / points; RegistrationParams::weight). 0: every point.
  double points_worth = 200;
  double max_correction = 1.5;     // m: a registration moving the guess farther is not taken
  double max_turn = 0.05;          // rad: nor one turning it more
  std::size_t min_matched = 100;   // points matched to the map, at least, for a registration to count
  // A direction of motion in which fewer than this many points' worth of surface faces (the sum
  // over the scan of n n^T, n each point's surface normal, has an eigenvalue below it) is not
  // one the scan can tell: there the pose and its variance are the prior's. Why: along a smooth
  // straight between smooth walls the registration still "finds" a motion, from how the voxel
  // means fall on the sampled surfaces (aliasing), and its Hessian claims as much information
  // along the track as across it.
  double min_support = 30;
  CovarianceParams covariances;
  // Each point's own voxel (DIRECT1: on these scans as accurate as DIRECT7 and 3.6 times
  // cheaper, docs/mapping.md), at most 16 iterations a stage, converged at 1 mm and 0.1 mrad.
  RegistrationParams registration{16, 1e-3, 1e-4, false};
};

struct ScanResult {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // map from vehicle: registered, else the guess
  bool registered = false;  // the registration converged, matched enough and was taken
  // The pose the frame joins the map on: `pose`; with the ground given (add's `ground`) and the
  // estimate GNSS's (`on_estimate`), the estimate's (x, y), the registration's heading (the
  // estimate's jitters by tenths of a degree, and a map stacked on it put a 10 s GNSS outage's
  // error at 0.36 m where it is 0.06 m) and the ground's roll, pitch and height: with GNSS the
  // fusion's position is better than the walls' registration (the mapped edges' p95 on
  // Hockenheim between two walls 0.126 m against 0.224 m; docs/mapping.md). Not while GNSS is
  // degraded: the fusion then takes `pose` as its update, and a map stacked on the estimate would
  // only confirm it (the outage's error 4.2 m).
  Eigen::Isometry3d map_pose = Eigen::Isometry3d::Identity();
  bool keyframe = false;    // the frame joined the map
  // The pose's covariance over (rotation omega, translation v), map frame: the registration's
  // system with the prior, inverted (the prior's alone when not registered).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity();
  std::size_t matched = 0;
  int iterations = 0;
  int degenerate = 0;  // directions of translation the scan could not tell (the prior's there)
};

class ScanMapper {
 public:
  explicit ScanMapper(ScanMapperParams p = {});
  const ScanMapperParams& params() const { return p_; }

  // One frame (vehicle frame) with the pose estimate `guess` (map from vehicle) and its
  // information (the prior; zero: none). The first frame starts the map on the guess.
  // `ground`, the frame's ground points (also in `scan`): the roll, pitch and height the frame
  // joins the map with are taken from them alone (level_on_ground); `tilt` is then turned out of
  // that roll and pitch (a part of the drift gravity finds, gravity_tilt.hpp; zero: none).
  // `on_estimate` (with the ground): the frame joins on the estimate's (x, y); say so only while
  // the estimate is its GNSS's (ScanResult::map_pose). The pose found (`pose`) is the whole
  // frame's registration either way.
  ScanResult add(const Points& scan, const Eigen::Isometry3d& guess, const Eigen::Matrix<double, 6, 6>& information,
                 const Points* ground = nullptr, const Tilt& tilt = {}, bool on_estimate = true);

  const VoxelMap& fine_map() const { return fine_; }
  const VoxelMap& coarse_map() const { return coarse_; }
  std::size_t keyframes() const { return keyframes_; }

 private:
  // Where the scan's surfaces tell nothing (ScanMapperParams::min_support): the guess's
  // translation and the prior's variance.
  void keep_prior_where_unseen(const Surfaces& surfaces, const Eigen::Isometry3d& guess, ScanResult& out) const;
  // The pose's roll, pitch and height from the ground alone, its (x, y, yaw) held at `from`'s;
  // none when that registration fails. Why: walls tilt the whole frame's registration; between
  // two walls it put the car's roll degrees off within seconds (the banking 2.7 deg off on flat
  // Hockenheim; docs/mapping.md).
  std::optional<Eigen::Isometry3d> level_on_ground(const Points& ground, const Eigen::Isometry3d& from) const;

  ScanMapperParams p_;
  std::optional<Eigen::Matrix<double, 6, 6>> prior_covariance_;  // of the frame being added
  VoxelMap coarse_, fine_;
  std::size_t keyframes_ = 0;
  Eigen::Vector3d last_key_ = Eigen::Vector3d::Constant(1e300);
};

// A frame thinned to one point (the mean of those in it) per voxel of `voxel` m, within
// `max_range` of the car; in first-met order.
Points thinned(const Points& scan, float voxel, double max_range);

// The directions of translation a frame's surfaces cannot tell (ScanMapperParams::min_support):
// the sum over the frame of n n^T (n each point's surface normal, turned into the map by `R`) has
// an eigenvalue below `min_support` along each. `epsilon`: the surfaces' regularization
// (CovarianceParams::epsilon).
struct Unseen {
  Eigen::Matrix3d projector = Eigen::Matrix3d::Zero();  // onto those directions
  int count = 0;
};
Unseen unseen_directions(const Surfaces& surfaces, const Eigen::Matrix3d& R, double epsilon, double min_support);

// The (x, y, yaw) covariance of a pose covariance over (omega, v): rows and columns v_x, v_y, omega_z.
Eigen::Matrix3d planar_covariance(const Eigen::Matrix<double, 6, 6>& c);
// The information over (omega, v) of a planar (x, y, yaw) covariance; roll, pitch and z get `weak`
// (a small information: the scan fixes them).
Eigen::Matrix<double, 6, 6> planar_information(const Eigen::Matrix3d& xy_yaw, double weak = 1e-6);

// A pose's pitch and roll (z-y-x order, the car never upside down): the small angles they are.
inline double pitch_of(const Eigen::Isometry3d& pose) {
  const double s = pose.linear()(2, 0);
  return -std::asin(s < -1 ? -1.0 : s > 1 ? 1.0 : s);
}
inline double roll_of(const Eigen::Isometry3d& pose) {
  const double s = pose.linear()(2, 1) / std::cos(pitch_of(pose));
  return std::asin(s < -1 ? -1.0 : s > 1 ? 1.0 : s);
}
inline double heading_of(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d fwd = pose.linear().col(0);
  return std::atan2(fwd.y(), fwd.x());
}
// The rotation of a heading, pitch and roll (z-y-x order).
inline Eigen::Matrix3d attitude(double heading, double pitch, double roll) {
  return (Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace brickyard::mapping
