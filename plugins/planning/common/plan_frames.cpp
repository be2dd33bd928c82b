#include "plan_frames.hpp"

#include <algorithm>
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

PoseSpread pose_spread(double var_x, double var_y, double var_yaw) {
  return {std::sqrt(std::max({var_x, var_y, 0.0})), std::sqrt(std::max(var_yaw, 0.0))};
}

std::optional<StampedPose> pose_at(const PoseHistory& history, std::int64_t stamp) {
  const auto at = history.at(stamp);
  if (!at) return std::nullopt;
  const PoseSpread& spread = at->nearer->estimate;
  return StampedPose{at->interpolated ? stamp : at->nearer->stamp_ns, at->pose.x, at->pose.y, at->pose.yaw, spread.position, spread.yaw};
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

std::size_t place_detections(const StampedPose& at, const std::vector<Detection>& list, const track::Track* track, double edge_band,
                             double sigmas, std::vector<MapObstacle>& seen) {
  std::size_t off_track = 0;
  for (const Detection& o : list)
    if (auto m = obstacle_in_map(at, o.x, o.y, o.size_x, o.size_y)) {
      if (track && !on_track(*track, m->x, m->y, placement_band(at, o.x, o.y, edge_band, sigmas))) ++off_track;
      else seen.push_back(*m);
    }
  return off_track;
}

}  // namespace brickyard::planning
