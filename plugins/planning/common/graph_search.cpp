#include "graph_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::planning {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint32_t kNone = ~std::uint32_t{0};
}  // namespace

double relative_s(double s, double s0, double length) {
  double r = std::fmod(s - s0, length);
  if (r < 0) r += length;
  return r > 0.5 * length ? r - length : r;
}

bool edge_blocked(const EdgeShape& e, const FrenetObstacle& o, double half_width, const SearchParams& p,
                  double* side_gap, double from) {
  // The car's reference point runs along the edge; the car covers [s - rear, s + front] of the
  // line, so it is beside the obstacle while s is in this window.
  const double w0 = std::max({e.s_a, from, o.s - p.car_front - o.radius}), w1 = std::min(e.s_b, o.s + p.car_rear + o.radius);
  if (w0 > w1) {
    if (side_gap) *side_gap = kInf;
    return false;
  }
  // d is monotonic along an edge: over the window it spans [d(w0), d(w1)].
  const double a = e.d(w0), b = e.d(w1), lo = std::min(a, b), hi = std::max(a, b);
  const double apart = o.d < lo ? lo - o.d : o.d > hi ? o.d - hi : 0.0;
  const double gap = apart - o.radius - half_width;
  if (side_gap) *side_gap = gap;
  return gap < p.clearance;
}

GraphSearch::GraphSearch(const RoadGraph& g) : g_(g), cost_(g.node_count(), kInf), parent_(g.node_count(), kNone) {}

namespace {
// Obstacles relative to the start, those that can matter only.
std::vector<FrenetObstacle> obstacles_near(const std::vector<FrenetObstacle>& obstacles, double s0, double length, double horizon,
                                           double reach, const SearchParams& p) {
  std::vector<FrenetObstacle> near;
  for (const auto& o : obstacles) {
    FrenetObstacle r = o;
    r.s = relative_s(o.s, s0, length);
    if (r.s > -p.car_rear - r.radius - 1 && r.s < horizon + reach + p.car_front + r.radius + 1) near.push_back(r);
  }
  return near;
}
}  // namespace

// One search's frame: s measured from the start node's layer on round the loop, the horizon and
// the start's layer.
struct GraphSearch::Frame {
  const std::vector<RoadGraph::Layer>& layers;
  double s0, length, reach, horizon, half_width;
  int l0;
  double rel(int layer) const {
    double r = layers[layer].s - s0;
    return r < 0 ? r + length : r;
  }
};

Plan GraphSearch::plan(const std::vector<std::pair<std::uint32_t, double>>& starts, const std::vector<FrenetObstacle>& obstacles,
                       const SearchParams& p) {
  for (std::uint32_t n : touched_) { cost_[n] = kInf; parent_[n] = kNone; }
  touched_.clear();
  Plan out;
  if (starts.empty()) return out;
  const std::uint32_t start = starts.front().first;
  const double length = g_.length(), reach = g_.params().max_edge_length;
  const double horizon = std::min(p.horizon, length - reach - 1.0);
  const double s0 = g_.node_s(start), hw = g_.params().half_width;
  const std::vector<FrenetObstacle> near = obstacles_near(obstacles, s0, length, horizon, reach, p);
  const Frame fr{g_.layers(), s0, length, reach, horizon, hw, g_.layer_of(start)};
  seed_starts(starts, fr.l0);
  relax_layers(fr, near, p, out);
  const auto [best, best_cost] = cheapest_end(fr, p);
  if (best == kNone) return out;
  out.found = true;
  out.cost = best_cost;
  // Parents lead back layer by layer to a start: at most one node per layer.
  for (std::uint32_t n = best; n != kNone && out.nodes.size() <= fr.layers.size(); n = parent_[n]) out.nodes.push_back(n);
  std::reverse(out.nodes.begin(), out.nodes.end());
  return out;
}

void GraphSearch::seed_starts(const std::vector<std::pair<std::uint32_t, double>>& starts, int l0) {
  for (const auto& [n, c] : starts) {
    if (g_.layer_of(n) != l0 || !(c >= 0) || cost_[n] != kInf) continue;  // one layer, each once
    cost_[n] = c;
    touched_.push_back(n);
  }
}

void GraphSearch::relax_layers(const Frame& fr, const std::vector<FrenetObstacle>& near, const SearchParams& p, Plan& out) {
  const int nl = static_cast<int>(fr.layers.size());
  for (int off = 0; off < nl; ++off) {
    const int l = (fr.l0 + off) % nl;
    const double ra = off == 0 ? 0.0 : fr.rel(l);
    if (off > 0 && ra >= fr.horizon) break;
    const auto& L = fr.layers[l];
    for (std::uint32_t n = L.first_node; n < L.first_node + L.count; ++n) {
      if (cost_[n] == kInf) continue;
      relax_node(fr, n, ra, near, p, out);
    }
  }
}

void GraphSearch::relax_node(const Frame& fr, std::uint32_t n, double ra, const std::vector<FrenetObstacle>& near,
                             const SearchParams& p, Plan& out) {
  const double da = g_.node_d(n);
  // A node's edges come grouped by the layer they lead to: the target layer's s and the
  // obstacles beside the stretch between are worked out once per group.
  int to_layer = -1;
  double rb = 0;
  for (const auto* e = g_.edges_begin(n); e != g_.edges_end(n); ++e) {
    ++out.edges_relaxed;
    if (g_.layer_of(e->to) != to_layer) {
      to_layer = g_.layer_of(e->to);
      rb = fr.rel(to_layer);
      if (rb <= ra) rb += fr.length;
      beside_.clear();
      for (const auto& o : near)
        if (o.s - p.car_front - o.radius <= rb && o.s + p.car_rear + o.radius >= ra) beside_.push_back(o);
    }
    if (p.lateral_accel > 0 && std::abs(g_.node_d(e->to) - da) > 1e-9 &&
        e->max_kappa * reachable_speed2(p, p.ahead + ra) > p.lateral_accel)
      continue;  // a lane change sharper than the car can be slow enough for
    const EdgeShape shape{ra, da, rb, g_.node_d(e->to)};
    double c = p.k_length * e->length + p.k_curvature * e->curvature + p.k_deviation * e->deviation;
    if (!add_proximity_cost(shape, *e, fr.half_width, p, c)) continue;  // blocked
    const double total = cost_[n] + c;
    if (total < cost_[e->to]) {
      if (cost_[e->to] == kInf) touched_.push_back(e->to);
      cost_[e->to] = total;
      parent_[e->to] = n;
    }
  }
}

bool GraphSearch::add_proximity_cost(const EdgeShape& shape, const RoadGraph::Edge& e, double hw, const SearchParams& p,
                                     double& c) const {
  for (const auto& o : beside_) {
    double gap;
    if (edge_blocked(shape, o, swept_half_width(hw, e.max_kappa, p), p, &gap)) return false;
    if (gap < p.soft_clearance) c += p.k_proximity * (p.soft_clearance - gap) * (p.soft_clearance - gap);
  }
  return true;
}

std::pair<std::uint32_t, double> GraphSearch::cheapest_end(const Frame& fr, const SearchParams& p) const {
  // Ends: nodes past the horizon (reached by an edge from before it), each costed on to the same
  // s as a parallel to the line.
  const double s_end = fr.horizon + fr.reach;
  std::uint32_t best = kNone;
  double best_cost = kInf;
  for (std::uint32_t n : touched_) {
    const double rn = fr.rel(g_.layer_of(n));
    if (rn < fr.horizon || g_.layer_of(n) == fr.l0) continue;
    const double total = cost_[n] + std::max(0.0, s_end - rn) * (p.k_length + p.k_deviation * std::abs(g_.node_d(n)));
    if (total < best_cost || (total == best_cost && n < best)) { best_cost = total; best = n; }  // ties: lowest node
  }
  return {best, best_cost};
}

}  // namespace brickyard::planning
