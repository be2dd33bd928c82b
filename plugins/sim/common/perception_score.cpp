#include "perception_score.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

double wall_y_in_body(const Track& track, const Eigen::Isometry3d& world_from_body, int side) {
  double u = 0;
  for (int it = 0; it < 50; ++it) {
    const Eigen::Vector3d p = world_from_body * Eigen::Vector3d(0, u, 0);
    const Frenet f = track.project(p.x(), p.y());
    const double wall = side < 0 ? track.wall_right_d(f.seg, f.u) : track.wall_left_d(f.seg, f.u);
    if (!std::isfinite(wall)) return NAN;
    const double step = wall - f.d;  // d grows with body y (left) at about a metre per metre
    u += step;
    if (std::abs(step) < 1e-6) break;
  }
  return u;
}

Eigen::Vector3d pylon_in_body(const Track& track, const Eigen::Isometry3d& world_from_body, std::size_t i) {
  const Pylon& p = track.spec().pylons.at(i);
  return world_from_body.inverse() * Eigen::Vector3d(p.x, p.y, p.z + 0.5 * p.height);
}

void PerceptionScore::truth(std::int64_t stamp_ns, const Eigen::Isometry3d& world_from_body) {
  truth_.emplace_back(stamp_ns, world_from_body);
  while (truth_.size() > 4096) truth_.pop_front();
}

const Eigen::Isometry3d* PerceptionScore::pose_at(std::int64_t stamp_ns) const {
  // The newest truth at or before the stamp: what the LiDAR scanned from.
  auto it = std::upper_bound(truth_.begin(), truth_.end(), stamp_ns,
                             [](std::int64_t t, const auto& e) { return t < e.first; });
  if (it == truth_.begin()) return nullptr;
  return &std::prev(it)->second;
}

bool PerceptionScore::wall(std::int64_t stamp_ns, double distance, bool valid) {
  const Eigen::Isometry3d* pose = pose_at(stamp_ns);
  if (!pose) return false;
  const double truth = wall_y_in_body(track_, *pose, p_.wall_side);
  if (!std::isfinite(truth)) return true;  // no wall there: nothing to score
  ++wall_frames_;
  if (valid && std::isfinite(distance)) wall_errors_.push_back(std::abs(distance - truth));
  return true;
}

bool PerceptionScore::obstacles(std::int64_t stamp_ns, const std::vector<Eigen::Vector2d>& xy) {
  const Eigen::Isometry3d* pose = pose_at(stamp_ns);
  if (!pose) return false;
  ++obstacle_frames_;
  const std::size_t pylons = track_.spec().pylons.size();
  pylon_seen_.resize(pylons);
  std::vector<Eigen::Vector2d> at(pylons);
  for (std::size_t k = 0; k < pylons; ++k) at[k] = pylon_in_body(track_, *pose, k).head<2>();
  for (const auto& o : xy) {
    bool matched = false;
    for (const auto& a : at) matched = matched || (o - a).norm() < p_.match_radius;
    false_obstacles_ += !matched;

  }
  for (std::size_t k = 0; k < pylons; ++k) {
    const double dist = at[k].norm();
    if (at[k].x() < p_.min_range || dist > p_.max_range) continue;
    bool hit = false;
    for (const auto& o : xy) hit = hit || (o - at[k]).norm() < p_.match_radius;
    pylon_seen_[k].emplace_back(dist, hit);
  }
  return true;
}

std::vector<double> PerceptionScore::pylon_ranges() const {
  std::vector<double> out(track_.spec().pylons.size(), NAN);
  for (std::size_t k = 0; k < pylon_seen_.size(); ++k) {
    if (pylon_seen_[k].empty()) continue;
    auto seen = pylon_seen_[k];
    std::sort(seen.begin(), seen.end());
    double reliable = 0;
    for (const auto& [d, hit] : seen) {
      if (!hit) break;
      reliable = d;
    }
    out[k] = reliable;
  }
  return out;
}

double PerceptionScore::percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double rank = std::ceil(q * static_cast<double>(v.size()));
  return v[static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(v.size()))) - 1];
}

}  // namespace brickyard::sim
