#include "map_localization_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace brickyard::mapping {

MapLocalizationRun::MapLocalizationRun(const Points& map, const MapLocalizationRunParams& p)
    : localizer_(map, p.localizer), max_age_ns_(static_cast<std::int64_t>(p.max_estimate_age * 1e9)),
      min_interval_ns_(static_cast<std::int64_t>(p.min_interval_s * 1e9)),
      normal_interval_ns_(static_cast<std::int64_t>(std::max(p.min_interval_s, p.normal_interval_s) * 1e9)) {}

void MapLocalizationRun::estimate(std::int64_t stamp_ns, const math::PlanarPose& pose, const EstimateExtras& extras) {
  estimates_.add(stamp_ns, pose, extras);
}

std::optional<FramePose> MapLocalizationRun::frame(std::int64_t stamp, const Points& pts) {
  const auto pose_at = estimates_.at(stamp);
  const auto* est = pose_at ? pose_at->nearer : nullptr;
  const bool normal = est && est->estimate.status == 0;
  if (tried_ && stamp - last_tried_ns_ < (normal ? normal_interval_ns_ : min_interval_ns_) && stamp >= last_tried_ns_) {
    ++skipped_;
    return std::nullopt;
  }
  if (!est || std::llabs(est->stamp_ns - stamp) > max_age_ns_ || !std::isfinite(pose_at->pose.x) ||
      !std::isfinite(pose_at->pose.y) || !std::isfinite(pose_at->pose.yaw)) {
    ++no_estimate_;
    return std::nullopt;
  }
  ++frames_;
  tried_ = true;
  last_tried_ns_ = stamp;
  // The guess: the estimate's (x, y, yaw) with the height, roll and pitch the last located frame
  // found (the estimate is planar; a banked turn tilts the car).
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  guess.linear() = attitude(pose_at->pose.yaw, pitch_, roll_);
  guess.translation() = Eigen::Vector3d(pose_at->pose.x, pose_at->pose.y, z_);
  const Located r = localizer_.locate(pts, guess);
  ++failures_[static_cast<int>(r.failure)];
  Eigen::Matrix3d guess_cov;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) guess_cov(a, b) = est->estimate.covariance[3 * a + b];
  if (r.registered) {
    ++located_;
    unseen_frames_ += r.unseen > 0;
    correction_sum_ += r.correction;
    correction_max_ = std::max(correction_max_, r.correction);
    pitch_ = pitch_of(r.pose);
    roll_ = roll_of(r.pose);
    z_ = r.pose.translation().z();
  }
  return pose_of(stamp, r, est->estimate, guess_cov);
}

FramePose MapLocalizationRun::pose_of(std::int64_t stamp, const Located& r, const EstimateExtras& est,
                                      const Eigen::Matrix3d& guess_cov) const {
  FramePose out;
  out.stamp_ns = stamp;
  out.x = r.pose.translation().x();
  out.y = r.pose.translation().y();
  out.yaw = heading_of(r.pose);
  out.speed = est.speed;
  out.yaw_rate = est.yaw_rate;
  const Eigen::Matrix3d pc = r.registered ? planar_covariance(r.covariance) : guess_cov;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out.covariance[3 * a + b] = pc(a, b);
  out.update_case = r.registered ? 2 : 0;
  out.status = est.status;
  out.map_pose = r.pose;
  return out;
}

std::vector<std::pair<std::string, double>> MapLocalizationRun::metrics() const {
  auto n = [](std::uint64_t v) { return static_cast<double>(v); };
  return {{"map_points", n(localizer_.map_points())},
          {"frames", n(frames_)},
          {"located", n(located_)},
          {"located_with_unseen_direction", n(unseen_frames_)},
          {"not_located_too_few_points", n(failures_[static_cast<int>(LocateFailure::too_few_points)])},
          {"not_located_not_converged", n(failures_[static_cast<int>(LocateFailure::not_converged)])},
          {"not_located_too_few_matched", n(failures_[static_cast<int>(LocateFailure::too_few_matched)])},
          {"not_located_implausible", n(failures_[static_cast<int>(LocateFailure::implausible)])},
          {"not_located_singular", n(failures_[static_cast<int>(LocateFailure::singular)])},
          {"frames_without_estimate", n(no_estimate_)},
          {"frames_skipped", n(skipped_)},
          {"malformed_clouds", n(malformed_)},
          {"correction_mean_m", located_ ? correction_sum_ / n(located_) : 0.0},
          {"correction_max_m", correction_max_}};
}

}  // namespace brickyard::mapping
