#include "scan_mapper.hpp"

#include <Eigen/Eigenvalues>

#include "perception/common/cell_map.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

namespace {
constexpr int kWz = 2, kVx = 3, kVy = 4;  // (omega, v) indices of yaw, x and y
constexpr double kHold = 1e10;  // a prior's information that holds a coordinate where it is
}

ScanMapper::ScanMapper(ScanMapperParams p) : p_(p), coarse_(p.coarse_voxel), fine_(p.fine_voxel) {}

ScanResult ScanMapper::add(const Points& scan, const Eigen::Isometry3d& guess, const Eigen::Matrix<double, 6, 6>& information,
                           const Points* ground, const Tilt& tilt, bool on_estimate) {
  ScanResult out;
  out.pose = out.map_pose = guess;
  const Points near = thinned(scan, p_.scan_voxel, p_.max_range);
  const Surfaces surfaces = point_surfaces(near, p_.covariances);
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> prior_lu(information);
  prior_covariance_.reset();
  if (prior_lu.isInvertible()) {
    out.covariance = prior_lu.inverse();
    prior_covariance_ = out.covariance;
  }

  if (fine_.size() > 0 && !near.empty()) {
    // With the ground given: the roll, pitch and height from it alone, for the pose the frame
    // joins the map on (ScanResult::map_pose). The pose published is the whole frame's
    // registration below, not held at the ground's attitude: held, its (x, y) were worse in a
    // GNSS outage (docs/mapping.md).
    std::optional<Eigen::Isometry3d> level;
    if (ground) level = level_on_ground(*ground, guess);
    if (level && (tilt.roll != 0 || tilt.pitch != 0))  // turned about the car's own position
      level->linear() = attitude(heading_of(*level), pitch_of(*level) - tilt.pitch, roll_of(*level) - tilt.roll);
    if (level && on_estimate) out.map_pose = *level;
    PosePrior prior{guess, information};
    RegistrationParams rp = p_.registration;
    if (p_.points_worth > 0) rp.weight *= std::min(1.0, p_.points_worth / static_cast<double>(near.size()));
    const RegistrationResult r = register_scan(near, surfaces, {&coarse_, &fine_}, guess, rp, &prior);
    out.matched = r.matched;
    out.iterations = r.iterations;
    const Eigen::Isometry3d moved = guess.inverse() * r.transform;
    const bool plausible = moved.translation().norm() <= p_.max_correction &&
                           Eigen::AngleAxisd(moved.linear()).angle() <= p_.max_turn;
    if (r.converged && r.matched >= p_.min_matched && plausible) {
      const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(r.hessian);
      if (lu.isInvertible()) {
        out.pose = r.transform;
        out.covariance = lu.inverse();
        out.registered = true;
        keep_prior_where_unseen(surfaces, guess, out);
        if (!(level && on_estimate)) {
          out.map_pose = out.pose;
        } else {  // the registration's heading: the estimate's jitters by tenths of a degree
          out.map_pose.linear() = attitude(heading_of(out.pose), pitch_of(*level), roll_of(*level));
        }
      }
    }
  }
  // A frame joins the map (on map_pose) once the car has moved keyframe_distance since the last
  // one: a car standing still does not pile up the same scan.
  if (fine_.size() == 0 || (out.map_pose.translation() - last_key_).norm() >= p_.keyframe_distance) {
    Points world(near.size());
    Covariances wcovs(near.size());
    const Eigen::Matrix3f R = out.map_pose.linear().cast<float>();
    const Eigen::Vector3f t = out.map_pose.translation().cast<float>();
    for (std::size_t i = 0; i < near.size(); ++i) {
      world[i] = R * near[i] + t;
      wcovs[i] = covariance_of(R * surfaces[i]);
    }
    coarse_.add(world, wcovs);
    fine_.add(world, wcovs);
    last_key_ = out.map_pose.translation();
    ++keyframes_;
    out.keyframe = true;
  }
  return out;
}

std::optional<Eigen::Isometry3d> ScanMapper::level_on_ground(const Points& ground, const Eigen::Isometry3d& from) const {
  const Points near = thinned(ground, p_.scan_voxel, p_.max_range);
  if (near.size() < p_.min_matched) return std::nullopt;
  const Surfaces surfaces = point_surfaces(near, p_.covariances);
  // The (x, y, yaw) held at `from`'s (flat ground cannot tell them); roll, pitch and height free.
  Eigen::Matrix<double, 6, 6> hold = Eigen::Matrix<double, 6, 6>::Identity() * 1e-6;
  hold(kWz, kWz) = hold(kVx, kVx) = hold(kVy, kVy) = kHold;
  const PosePrior prior{from, hold};
  RegistrationParams rp = p_.registration;
  if (p_.points_worth > 0) rp.weight *= std::min(1.0, p_.points_worth / static_cast<double>(near.size()));
  const RegistrationResult r = register_scan(near, surfaces, {&coarse_, &fine_}, from, rp, &prior);
  const Eigen::Isometry3d moved = from.inverse() * r.transform;
  if (!r.converged || r.matched < p_.min_matched || moved.translation().norm() > p_.max_correction ||
      Eigen::AngleAxisd(moved.linear()).angle() > p_.max_turn)
    return std::nullopt;
  return r.transform;
}

Points thinned(const Points& scan, float voxel, double max_range) {
  const float r2 = static_cast<float>(max_range * max_range), inv = 1.0f / voxel;
  perception::CellMap<std::uint32_t> cells;
  cells.reset(scan.size());
  Points sum;
  std::vector<std::uint32_t> count;
  for (const Point& q : scan) {
    if (!perception::in_range(q) || q.squaredNorm() > r2) continue;
    bool inserted;
    const std::uint32_t c = cells.find_or_insert(
        perception::cell_key(perception::cell_of(q.x(), inv), perception::cell_of(q.y(), inv), perception::cell_of(q.z(), inv)),
        static_cast<std::uint32_t>(sum.size()), inserted);
    if (inserted) {
      sum.push_back(Point::Zero());
      count.push_back(0);
    }
    sum[c] += q;
    ++count[c];
  }
  for (std::size_t i = 0; i < sum.size(); ++i) sum[i] /= static_cast<float>(count[i]);
  return sum;
}

Unseen unseen_directions(const Surfaces& surfaces, const Eigen::Matrix3d& R, double epsilon, double min_support) {
  // The surfaces' normals, summed as n n^T: a point's surface s is sqrt(1 - eps) n. (A point with
  // too few neighbours has s = 0: it faces nowhere.)
  Eigen::Matrix3d support = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3f& s : surfaces) support += (s * s.transpose()).cast<double>();
  support = R * support * R.transpose() / (1.0 - epsilon);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(support);
  Unseen out;
  for (int k = 0; k < 3; ++k)
    if (es.eigenvalues()(k) < min_support) {
      out.projector += es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose();
      ++out.count;
    }
  return out;
}

void ScanMapper::keep_prior_where_unseen(const Surfaces& surfaces, const Eigen::Isometry3d& guess, ScanResult& out) const {
  const Unseen u = unseen_directions(surfaces, out.pose.linear(), p_.covariances.epsilon, p_.min_support);
  out.degenerate = u.count;
  if (out.degenerate == 0) return;
  const Eigen::Matrix3d& unseen = u.projector;
  // There: the guess's translation, and the prior's variance (its covariance, inverted from
  // the information the caller gave; without one, the registration's stays).
  out.pose.translation() += unseen * (guess.translation() - out.pose.translation());
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Identity();
  M.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() - unseen;
  Eigen::Matrix<double, 6, 6> c = M * out.covariance * M.transpose();
  if (prior_covariance_) c.bottomRightCorner<3, 3>() += unseen * prior_covariance_->bottomRightCorner<3, 3>() * unseen;
  out.covariance = c;
}

Eigen::Matrix3d planar_covariance(const Eigen::Matrix<double, 6, 6>& c) {
  const int idx[3] = {kVx, kVy, kWz};
  Eigen::Matrix3d out;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out(a, b) = c(idx[a], idx[b]);
  return out;
}

Eigen::Matrix<double, 6, 6> planar_information(const Eigen::Matrix3d& xy_yaw, double weak) {
  Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Identity() * weak;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(xy_yaw);
  if (!xy_yaw.allFinite() || !lu.isInvertible()) return info;
  const Eigen::Matrix3d inv = lu.inverse();
  const int idx[3] = {kVx, kVy, kWz};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) info(idx[a], idx[b]) = inv(a, b);
  return info;
}

}  // namespace brickyard::mapping
