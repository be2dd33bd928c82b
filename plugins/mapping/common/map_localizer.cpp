#include "map_localizer.hpp"

#include "scan_mapper.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <thread>

namespace brickyard::mapping {

namespace {
constexpr double kHold = 1e6;  // a prior's information that holds a coordinate at the guess (1 mm)
// The frame's height search stops at a height that holds this share of the frame's points, once
// it has looked this far past it both ways (m).
constexpr double kHeightShare = 0.6;
constexpr double kHeightSettle = 1.5;

// The heading turned from `a` to `b` (roll and pitch are the map's to say: the guess carries the
// last frame's), wrapped to [-pi, pi].
double heading_turn(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::remainder(heading_of(b) - heading_of(a), 2 * M_PI);
}

// Each surface within `tilt` of `up` turned to face `up` (its strength kept): a level disc.
void level_ground(Surfaces& surfaces, const Eigen::Vector3f& up, double tilt) {
  if (tilt <= 0) return;
  const float cos_tilt = static_cast<float>(std::cos(tilt));
  for (Eigen::Vector3f& s : surfaces) {
    const float strength = s.norm();
    if (strength == 0) continue;
    const float facing = s.dot(up) / strength;
    if (std::abs(facing) >= cos_tilt) s = (facing > 0 ? strength : -strength) * up;
  }
}

}  // namespace

const char* failure_name(LocateFailure f) {
  switch (f) {
    case LocateFailure::none: return "none";
    case LocateFailure::too_few_points: return "too few points";
    case LocateFailure::not_converged: return "not converged";
    case LocateFailure::too_few_matched: return "too few points matched to the map";
    case LocateFailure::implausible: return "too far from the guess";
    case LocateFailure::singular: return "singular";
  }
  return "?";
}

MapLocalizer::MapLocalizer(const Points& map, MapLocalizerParams p)
    : p_(p), coarse_(p.coarse_voxel), fine_(p.fine_voxel), points_(map.size()) {
  // Each map point's surface from its neighbours in the map, as the mapper's frames had theirs.
  Surfaces surfaces = point_surfaces(map, p_.covariances, p_.threads);
  level_ground(surfaces, Eigen::Vector3f::UnitZ(), p_.ground_tilt);
  Covariances covs(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) covs[i] = covariance_of(surfaces[i]);
  // The two voxel maps are apart: built side by side, each as it would be alone.
  if (p_.threads >= 2) {
    std::thread coarse([&] { coarse_.add(map, covs); });
    fine_.add(map, covs);
    coarse.join();
  } else {
    coarse_.add(map, covs);
    fine_.add(map, covs);
  }
}

double MapLocalizer::height_on_map(const Points& near, const Eigen::Isometry3d& guess) const {
  const double step = 0.5 * coarse_.voxel_size(), z0 = guess.translation().z();
  const int reach = static_cast<int>(p_.height_search / step);
  const int settle_steps = static_cast<int>(std::ceil(kHeightSettle / step));
  Points placed;
  for (std::size_t i = 0; i < near.size(); i += 8) placed.push_back((guess * near[i].cast<double>()).cast<float>());
  double best_z = z0;
  std::size_t best = 0;
  int best_j = 0;
  for (int k = 0; k <= 2 * reach; ++k) {  // 0, +1, -1, +2, -2, ...: the nearest first
    const int j = (k + 1) / 2 * (k % 2 ? 1 : -1);
    // Settled: a height most of the frame falls on, and none better within kHeightSettle past it
    // either way. The guess carries the last frame's height, so this is found within a few
    // steps; the whole search runs only where the map's height jumps (its loop's closure).
    const int searched = k / 2 - 1;  // every step within this of the guess's height
    if (k % 2 == 0 && searched >= std::abs(best_j) + settle_steps && best >= kHeightShare * placed.size()) break;
    const Eigen::Vector3f up(0, 0, static_cast<float>(j * step));
    std::size_t hits = 0;
    for (const Point& q : placed) hits += coarse_.target(Eigen::Vector3f(q + up)) != nullptr;
    if (hits > best) best = hits, best_z = z0 + j * step, best_j = j;
  }
  return best_z;
}

Surfaces MapLocalizer::frame_surfaces(const Points& near, const Eigen::Isometry3d& guess) const {
  Surfaces surfaces = point_surfaces(near, p_.covariances);
  const Eigen::Vector3f up = (guess.linear().transpose() * Eigen::Vector3d::UnitZ()).cast<float>();
  level_ground(surfaces, up, p_.ground_tilt);
  return surfaces;
}

Eigen::Matrix<double, 6, 6> MapLocalizer::weak_prior() const {
  Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Zero();
  info.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / (p_.prior_sigma_turn * p_.prior_sigma_turn));
  info.bottomRightCorner<3, 3>().diagonal().setConstant(1.0 / (p_.prior_sigma * p_.prior_sigma));
  return info;
}

Eigen::Matrix<double, 6, 6> MapLocalizer::prior_information(const Eigen::Matrix3d& unseen) const {
  Eigen::Matrix<double, 6, 6> info = weak_prior();
  info.bottomRightCorner<3, 3>() += kHold * unseen;
  return info;
}

Located MapLocalizer::locate(const Points& frame, Eigen::Isometry3d guess) const {
  Located out;
  out.pose = guess;
  const Points near = thinned(frame, p_.scan_voxel, p_.max_range);
  if (near.size() < p_.min_matched || fine_.size() == 0) {
    out.failure = LocateFailure::too_few_points;
    return out;
  }
  if (p_.height_search > 0) guess.translation().z() = height_on_map(near, guess);
  const Surfaces surfaces = frame_surfaces(near, guess);
  // Directions the frame cannot tell are held at the guess through the registration: left free
  // there, it wanders by aliasing (the voxel means slide along a smooth wall) and does not
  // converge. The frame's surfaces turned by the guess's attitude: a turn of a few hundredths of
  // a radian does not change which directions they face.
  const Unseen unseen = unseen_directions(surfaces, guess.linear(), p_.covariances.epsilon, p_.min_support);
  const PosePrior prior{guess, prior_information(unseen.projector)};
  RegistrationParams rp = p_.registration;
  if (p_.points_worth > 0) rp.weight *= std::min(1.0, p_.points_worth / static_cast<double>(near.size()));
  const RegistrationResult r = register_scan(near, surfaces, {&coarse_, &fine_}, guess, rp, &prior);
  out.matched = r.matched;
  out.iterations = r.iterations;
  // The covariance from what the frame told, without the weak prior's information: that is the
  // estimate's own, and a pose that carried it would be the estimate told back to itself (where
  // the frame tells little, a pose at the guess sure to prior_sigma, taken again every frame).
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(r.hessian - weak_prior());
  if (!r.converged) out.failure = LocateFailure::not_converged;
  else if (r.matched < p_.min_matched) out.failure = LocateFailure::too_few_matched;
  else if ((r.transform.translation() - guess.translation()).head<2>().norm() > p_.max_correction ||
           std::abs(heading_turn(guess, r.transform)) > p_.max_turn)
    out.failure = LocateFailure::implausible;
  else if (!lu.isInvertible()) out.failure = LocateFailure::singular;
  if (out.failure != LocateFailure::none) return out;
  out.pose = without_prior_pull(r, guess, lu);
  out.covariance = lu.inverse();
  out.registered = true;
  keep_guess_where_unseen(surfaces, guess, out);
  floor_position_spread(out.covariance);
  out.correction = (out.pose.translation() - guess.translation()).head<2>().norm();
  return out;
}

Eigen::Isometry3d MapLocalizer::without_prior_pull(const RegistrationResult& r, const Eigen::Isometry3d& guess,
                                                  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>>& frame_information) const {
  // One Gauss-Newton step of the frame's terms alone (the hold along unseen directions kept): the
  // gradient less the weak prior's, as the registration added it.
  const Eigen::Matrix<double, 6, 1> d = frame_information.solve(-(r.gradient - weak_prior() * prior_residual(guess, r.transform)));
  return d.allFinite() ? moved_by(d, r.transform) : r.transform;
}

void MapLocalizer::floor_position_spread(Eigen::Matrix<double, 6, 6>& covariance) const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(covariance.bottomRightCorner<3, 3>());
  const Eigen::Vector3d spread = es.eigenvalues().cwiseMax(p_.min_sigma * p_.min_sigma);
  covariance.bottomRightCorner<3, 3>() = es.eigenvectors() * spread.asDiagonal() * es.eigenvectors().transpose();
}

void MapLocalizer::keep_guess_where_unseen(const Surfaces& surfaces, const Eigen::Isometry3d& guess, Located& out) const {
  // Found again at the pose found: the spread along them is large enough that the guess's few
  // hundredths of a radian would leak it into the directions the frame tells.
  const Unseen u = unseen_directions(surfaces, out.pose.linear(), p_.covariances.epsilon, p_.min_support);
  out.unseen = u.count;
  if (u.count == 0) return;
  out.pose.translation() += u.projector * (guess.translation() - out.pose.translation());
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Identity();
  M.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() - u.projector;
  out.covariance = M * out.covariance * M.transpose();
  out.covariance.bottomRightCorner<3, 3>() += p_.unseen_sigma * p_.unseen_sigma * u.projector;
}

}  // namespace brickyard::mapping
