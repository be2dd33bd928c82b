#include "road_graph_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::planning {

RoadGraphPlanner::RoadGraphPlanner(const RoadGraph& graph, const RefLine& line, std::vector<double> ref_speed,
                                   PlannerParams p)
    : g_(graph), line_(line), ref_speed_(std::move(ref_speed)), p_(p), search_(graph) {
  if (static_cast<int>(ref_speed_.size()) != line.size())
    throw std::invalid_argument("road graph planner: one reference speed per point of the line");
}

void RoadGraphPlanner::observe(const std::vector<MapObstacle>& seen, std::int64_t now_ns) {
  for (const MapObstacle& o : seen) {
    MapObstacle* same = nullptr;
    double best = p_.merge_distance;
    for (MapObstacle& m : memory_) {
      const double d = std::hypot(m.x - o.x, m.y - o.y);
      if (d <= best) { best = d; same = &m; }
    }
    if (same) *same = o;
    else memory_.push_back(o);
    (same ? *same : memory_.back()).seen_ns = now_ns;
  }
  const auto keep_ns = static_cast<std::int64_t>(p_.obstacle_memory * 1e9);
  memory_.erase(std::remove_if(memory_.begin(), memory_.end(), [&](const MapObstacle& m) { return now_ns - m.seen_ns > keep_ns; }),
                memory_.end());
}

bool RoadGraphPlanner::committed_blocked(const std::vector<Piece>& pieces, const std::vector<FrenetObstacle>& obs) const {
  const double L = line_.length();
  for (const Piece& pc : pieces) {
    // In s relative to the piece's start, as the obstacles below.
    const EdgeShape e{0, pc.shape.d_a, pc.shape.s_b - pc.shape.s_a, pc.shape.d_b};
    for (const auto& o : obs) {
      FrenetObstacle r = o;
      r.s = relative_s(o.s, pc.shape.s_a, L);
      if (edge_blocked(e, r, g_.params().half_width, p_.search)) return true;
    }
  }
  return false;
}

const PlannedPath& RoadGraphPlanner::plan(double x, double y, double speed) {
  const double L = line_.length();
  const Eigen::Vector2d f = line_.to_frenet(x, y, hint_s_);
  const double s_c = f.x(), d_c = f.y();
  hint_s_ = s_c;
  std::vector<FrenetObstacle> obs;
  for (const MapObstacle& m : memory_) {
    const Eigen::Vector2d q = line_.to_frenet(m.x, m.y, s_c);
    obs.push_back({q.x(), q.y(), m.radius});
  }
  out_ = PlannedPath{};
  // What stays of the last plan: pieces not yet behind the car, up to the commitment point.
  const double commit = std::max(p_.commit_min, p_.commit_time * std::max(speed, 0.0));
  std::vector<Piece> kept;
  bool on_it = false;
  for (const Piece& pc : pieces_) {
    const double ra = relative_s(pc.shape.s_a, s_c, L), rb = ra + (pc.shape.s_b - pc.shape.s_a);
    if (rb < 0) continue;
    if (ra <= 0) on_it = std::abs(pc.shape.d(pc.shape.s_a - ra) - d_c) <= p_.rejoin;
    kept.push_back(pc);
    if (rb >= commit) break;
  }
  const bool reaches = !kept.empty() && relative_s(kept.back().shape.s_b, s_c, L) >= commit;
  if (!on_it || !reaches || committed_blocked(kept, obs)) {
    // Start afresh: a lead-in from behind the car at its offset to the node nearest it there.
    kept.clear();
    const int layer = g_.layer_at_or_after(s_c + commit);
    const std::uint32_t start = g_.nearest_node(layer, d_c);
    double h = g_.node_s(start) - s_c;
    if (h < 0) h += L;
    kept.push_back({EdgeShape{s_c - p_.behind, d_c, s_c + h, g_.node_d(start)}, start});
    out_.restarted = true;
  }
  const std::uint32_t start = kept.back().end;
  const Plan plan = search_.plan(start, obs, p_.search);
  out_.route_found = plan.found;
  out_.edges_relaxed = plan.edges_relaxed;
  for (std::size_t i = 1; i < plan.nodes.size(); ++i) {
    const std::uint32_t a = plan.nodes[i - 1], b = plan.nodes[i];
    double h = g_.node_s(b) - g_.node_s(a);
    if (h <= 0) h += L;
    const double sa = kept.back().shape.s_b;
    kept.push_back({EdgeShape{sa, g_.node_d(a), sa + h, g_.node_d(b)}, b});
  }
  pieces_ = kept;
  // The path: points along the pieces, then speeds within the line's profile and the path's bends.
  for (const Piece& pc : pieces_) sample_shape(line_, pc.shape, p_.path_step, out_.points);
  {
    const Piece& last = pieces_.back();
    const double s = last.shape.s_b, d = last.shape.d_b;
    const Eigen::Vector2d q = line_.point(s, d);
    out_.points.push_back({q.x(), q.y(), s, d, offset_curvature(line_.kappa(s), d, 0, 0)});
  }
  const std::size_t n = out_.points.size();
  std::vector<double> ds(n - 1), kappa(n), cap(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PathSample& q = out_.points[i];
    kappa[i] = q.kappa;
    cap[i] = line_.interpolate(ref_speed_, q.s);
    if (i + 1 < n) ds[i] = std::max(1e-3, std::hypot(out_.points[i + 1].x - q.x, out_.points[i + 1].y - q.y));
  }
  // No route: brake to a stop by the end of what the car is committed to.
  out_.speed = speed_profile(ds, kappa, p_.limits, false, -1, plan.found ? -1 : 0.0, &cap);
  return out_;
}

}  // namespace brickyard::planning
