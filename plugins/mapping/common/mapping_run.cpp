#include "mapping_run.hpp"

#include "pcd.hpp"

#include "track/centre_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

namespace brickyard::mapping {

std::string unwritable(const std::string& param, const std::string& path) {
  if (path.empty()) return {};
  const std::string probe = path + ".part";
  if (!std::ofstream(probe)) return param + " '" + path + "': cannot write there (does its folder exist?)";
  std::remove(probe.c_str());
  return {};
}

MappingRun::MappingRun(const MappingRunParams& p, bool road_surface)
    : mapper_(p.mapper),
      surface_(p.surface),
      extraction_(p.extraction),
      road_surface_(road_surface),
      max_age_ns_(static_cast<std::int64_t>(p.max_estimate_age * 1e9)),
      level_on_ground_(p.level_on_ground),
      tilt_(p.level_window),
      level_time_(p.level_time) {}

void MappingRun::estimate(std::int64_t stamp_ns, const math::PlanarPose& pose, const EstimateExtras& extras) {
  estimates_.add(stamp_ns, pose, extras);
}

void MappingRun::imu(std::int64_t stamp_ns, double accel_x, double accel_y, double yaw_rate) {
  if (!estimates_.empty()) tilt_.add_imu(stamp_ns, accel_x, accel_y, yaw_rate, estimates_.newest().estimate.speed);
}

std::optional<FramePose> MappingRun::frame(std::int64_t stamp, const Points& pts, std::size_t n_ground, bool imu_wired) {
  const auto pose_at = estimates_.at(stamp);
  const auto* est = pose_at ? pose_at->nearer : nullptr;
  if (!est || std::llabs(est->stamp_ns - stamp) > max_age_ns_ || !std::isfinite(est->pose.x) || !std::isfinite(est->pose.y) ||
      !std::isfinite(est->pose.yaw)) {
    ++no_estimate_;
    return std::nullopt;
  }
  const math::PlanarPose at = pose_at->pose;
  const double ex = at.x, ey = at.y, eyaw = at.yaw;
  ++frames_;
  // The guess: the estimate's (x, y, yaw), with the height, roll and pitch the last frame found
  // (the estimate is planar; a banked turn tilts the car).
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  guess.linear() = attitude(eyaw, pitch_, roll_);
  guess.translation() = Eigen::Vector3d(ex, ey, z_);
  Eigen::Matrix3d cov;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) cov(a, b) = est->estimate.covariance[3 * a + b];
  const Points ground_pts(pts.begin(), pts.begin() + static_cast<long>(n_ground));
  // Gravity's level: a part of the attitude's drift turned out each frame (GravityTilt).
  Tilt tilt;
  if (level_on_ground_ && imu_wired && tilt_.correction(stamp, level_time_, tilt)) ++levelled_;
  const ScanResult r = mapper_.add(pts, guess, planar_information(cov), level_on_ground_ ? &ground_pts : nullptr, tilt,
                                   est->estimate.status == 0);  // NORMAL: its GNSS's
  if (r.registered) {
    ++registered_;
    const double c = std::hypot(r.pose.translation().x() - ex, r.pose.translation().y() - ey);
    correction_sum_ += c;
    correction_max_ = std::max(correction_max_, c);
    pitch_ = pitch_of(r.map_pose);
    roll_ = roll_of(r.map_pose);
    z_ = r.map_pose.translation().z();
    tilt_.add_frame(stamp, roll_, pitch_);
  }
  if (road_surface_) {
    driven_.emplace_back(r.map_pose.translation().x(), r.map_pose.translation().y());
    driven_roll_.push_back(r.registered ? roll_of(r.map_pose) : NAN);
  }
  FramePose out;
  out.stamp_ns = stamp;
  out.x = r.pose.translation().x();
  out.y = r.pose.translation().y();
  const Eigen::Vector3d fwd = r.pose.linear().col(0);
  out.yaw = std::atan2(fwd.y(), fwd.x());
  out.speed = est->estimate.speed;
  out.yaw_rate = est->estimate.yaw_rate;
  const Eigen::Matrix3d pc = planar_covariance(r.covariance);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out.covariance[3 * a + b] = pc(a, b);
  out.update_case = r.registered ? 2 : 0;
  out.status = est->estimate.status;
  out.map_pose = r.map_pose;
  return out;
}

void MappingRun::add_scan(const float* x, const float* y, const float* z, const float* intensity, std::size_t n,
                          const Eigen::Isometry3d& vehicle_from_sensor, const Eigen::Isometry3d& map_pose) {
  if (road_surface_) surface_.add_scan(x, y, z, intensity, n, vehicle_from_sensor, map_pose);
}

std::vector<std::pair<std::string, double>> MappingRun::metrics() const {
  return {{"frames", static_cast<double>(frames_)},
          {"registered", static_cast<double>(registered_)},
          {"keyframes", static_cast<double>(mapper_.keyframes())},
          {"map_voxels", static_cast<double>(mapper_.fine_map().size())},
          {"frames_without_estimate", static_cast<double>(no_estimate_)},
          {"malformed_clouds", static_cast<double>(malformed_)},
          {"correction_mean_m", registered_ ? correction_sum_ / static_cast<double>(registered_) : 0.0},
          {"correction_max_m", correction_max_},
          {"road_cells", static_cast<double>(surface_.cells())},
          {"gravity_levelled_frames", static_cast<double>(levelled_)}};
}

FileWritten MappingRun::write_map(const std::string& path) const {
  try {
    write_pcd(path, mapper_.fine_map());
    return {true, "map written: " + path + " (" + std::to_string(mapper_.fine_map().size()) + " points)"};
  } catch (const std::exception& e) {
    return {false, e.what()};
  }
}

TrackWritten MappingRun::write_track(const std::string& path) const {
  TrackWritten out;
  try {
    const ExtractedTrack t = extract_track(surface_, driven_, extraction_, &driven_roll_);
    track::write_centerline_csv(path, t.line);
    out.ok = true;
    out.points = static_cast<double>(t.line.x.size());
    out.sides_found = static_cast<double>(t.sides_found) / (2.0 * static_cast<double>(t.stations));
    out.message = "track written: " + path + " (" + std::to_string(t.line.x.size()) + " points, edges found on " +
                  std::to_string(t.sides_found) + " of " + std::to_string(2 * t.stations) + " sides)";
  } catch (const std::exception& e) {
    out.error = e.what();
    out.message = "track_file '" + path + "' not written: " + e.what();
  }
  return out;
}

}  // namespace brickyard::mapping
