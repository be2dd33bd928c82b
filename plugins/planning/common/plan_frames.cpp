#include "plan_frames.hpp"

#include <algorithm>
#include "math/planar_pose.hpp"

#include <cmath>

namespace brickyard::planning {

std::optional<MapObstacle> obstacle_in_map(const StampedPose& at, double ox, double oy, double sx, double sy) {
  const double c = std::cos(at.yaw), sn = std::sin(at.yaw);
  MapObstacle m;
  m.x = at.x + c * ox - sn * oy;
  m.y = at.y + sn * ox + c * oy;
  if (!std::isfinite(m.x) || !std::isfinite(m.y)) return std::nullopt;
  const double r = 0.5 * std::max(sx, sy);
  m.radius = std::isfinite(r) ? std::clamp(r, 0.1, 5.0) : 5.0;
  // The spread of the place: the pose's position, its heading's error times the range, and a
  // tenth of a metre for where on the obstacle the points fell. Not a finite number: unknown
  // (the planner takes a metre).
  const double range = std::hypot(ox, oy), ys = at.yaw_sigma * range;
  m.variance = at.position_sigma * at.position_sigma + ys * ys + 0.01;
  if (!std::isfinite(m.variance)) m.variance = -1;
  return m;
}

int nearest_pose(const std::vector<StampedPose>& poses, std::int64_t stamp) {
  if (poses.empty()) return -1;
  auto apart = [stamp](const StampedPose& e) {
    return std::abs(static_cast<double>(e.stamp_ns) - static_cast<double>(stamp));
  };
  int best = static_cast<int>(poses.size()) - 1;
  for (int i = 0; i < static_cast<int>(poses.size()); ++i)
    if (apart(poses[i]) < apart(poses[best])) best = i;
  return best;
}

StampedPose pose_at(const std::vector<StampedPose>& poses, std::int64_t stamp) {
  const int n = nearest_pose(poses, stamp);
  if (n < 0) return {};
  int before = -1, after = -1;
  for (int i = 0; i < static_cast<int>(poses.size()); ++i) {
    const std::int64_t t = poses[i].stamp_ns;
    if (t <= stamp && (before < 0 || t > poses[before].stamp_ns)) before = i;
    if (t >= stamp && (after < 0 || t < poses[after].stamp_ns)) after = i;
  }
  if (before < 0 || after < 0 || poses[after].stamp_ns <= poses[before].stamp_ns) return poses[n];
  const StampedPose &a = poses[before], &b = poses[after];
  const math::PlanarPose q = math::interpolate_pose(a.stamp_ns, {a.x, a.y, a.yaw}, b.stamp_ns, {b.x, b.y, b.yaw}, stamp);
  StampedPose p = 2 * (stamp - a.stamp_ns) < b.stamp_ns - a.stamp_ns ? a : b;  // the spreads of the nearer (b at a tie)
  p.stamp_ns = stamp;
  p.x = q.x;
  p.y = q.y;
  p.yaw = q.yaw;
  return p;
}

PathGeometry path_geometry(const std::vector<PathSample>& pts) {
  PathGeometry g;
  double s = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::size_t j = i + 1 < pts.size() ? i + 1 : i;
    const std::size_t k = i + 1 < pts.size() ? i : i - 1;
    g.x.push_back(pts[i].x);
    g.y.push_back(pts[i].y);
    g.yaw.push_back(std::atan2(pts[j].y - pts[k].y, pts[j].x - pts[k].x));
    g.curvature.push_back(pts[i].kappa);
    if (i > 0) s += std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    g.s.push_back(s);
    g.max_offset = std::max(g.max_offset, std::abs(pts[i].d));
  }
  return g;
}

bool on_track(const track::Track& track, double x, double y, double edge_band, int hint) {
  if (!(std::isfinite(x) && std::isfinite(y))) return false;
  const track::Frenet f = track.project(x, y, hint);
  return f.d <= track.width_left(f.seg, f.u) - edge_band && -f.d <= track.width_right(f.seg, f.u) - edge_band;
}

double placement_band(const StampedPose& at, double ox, double oy, double edge_band, double sigmas) {
  const double spread = sigmas * (at.position_sigma + at.yaw_sigma * std::hypot(ox, oy));
  return std::isfinite(spread) && spread > 0 ? edge_band + spread : edge_band;
}

}  // namespace brickyard::planning
