#include "road_graph_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::planning {

namespace {
constexpr std::uint32_t kNoNode = ~std::uint32_t{0};  // a piece that ends off the graph

// The side gap of a car at offset d beside obstacle o (s relative to the car), infinite when the
// car's body is not beside it.
double gap_beside(const FrenetObstacle& o, double d, double half_width, const SearchParams& p) {
  double gap = std::numeric_limits<double>::infinity();
  edge_blocked(EdgeShape{0, d, 1e-3, d}, o, half_width, p, &gap, 0.0);
  return gap;
}
}  // namespace

RoadGraphPlanner::RoadGraphPlanner(const RoadGraph& graph, const RefLine& line, std::vector<double> ref_speed,
                                   PlannerParams p)
    : g_(graph), line_(line), ref_speed_(std::move(ref_speed)), p_(p), search_(graph) {
  if (static_cast<int>(ref_speed_.size()) != line.size())
    throw std::invalid_argument("road graph planner: one reference speed per point of the line");
}

void RoadGraphPlanner::observe(const std::vector<MapObstacle>& seen, std::int64_t now_ns) {
  // Each remembered obstacle takes at most one detection of a frame (the nearest within
  // merge_distance): two pylons side by side stay two, and a frame counts once.
  std::vector<char> matched(memory_.size(), 0);
  const std::size_t before = memory_.size();
  for (MapObstacle o : seen) {
    if (!(std::abs(o.x) < 1e7 && std::abs(o.y) < 1e7)) continue;  // NaN or absurd: not a place
    if (!(o.radius >= 0.05 && o.radius <= 5.0)) o.radius = 5.0;     // unknown size: the largest
    std::size_t same = before;
    double best = p_.merge_distance;
    for (std::size_t i = 0; i < before; ++i) {
      const double d = std::hypot(memory_[i].x - o.x, memory_[i].y - o.y);
      if (!matched[i] && d <= best) { best = d; same = i; }
    }
    if (!(o.variance > 0 && o.variance < 1e6)) o.variance = 1.0;  // an unknown spread: a metre
    if (same < before) {
      const MapObstacle& m = memory_[same];
      if (p_.obstacle_fusion) {
        // The remembered place and the detection fused by their variances (a Kalman update of a
        // place that may drift): the remembered one's grows by drift² a second since it was seen.
        const double dt = std::clamp(static_cast<double>(now_ns - m.seen_ns) * 1e-9, 0.0, 3600.0);
        const double p = m.variance + p_.obstacle_drift * p_.obstacle_drift * dt, k = p / (p + o.variance);
        o.x = m.x + k * (o.x - m.x);
        o.y = m.y + k * (o.y - m.y);
        o.radius = m.radius + k * (o.radius - m.radius);
        o.variance = (1 - k) * p;
      }
      o.seen = m.seen + 1;
      o.seen_ns = now_ns;
      memory_[same] = o;
      matched[same] = 1;
    } else {
      o.seen = 1;
      o.seen_ns = now_ns;
      memory_.push_back(o);
    }
  }
  const auto keep_ns = static_cast<std::int64_t>(std::clamp(p_.obstacle_memory, 0.0, 1e6) * 1e9);
  memory_.erase(std::remove_if(memory_.begin(), memory_.end(), [&](const MapObstacle& m) { return now_ns - m.seen_ns > keep_ns; }),
                memory_.end());
}

bool RoadGraphPlanner::committed_blocked(const std::vector<Piece>& pieces, const std::vector<FrenetObstacle>& obs,
                                         double s_c) const {
  if (obs.empty()) return false;
  const double L = line_.length();
  SearchParams keep = p_.search;
  keep.clearance = std::min(p_.keep_clearance, p_.search.clearance);
  for (const Piece& pc : pieces) {
    // In s relative to the piece's start, as the obstacles below.
    const EdgeShape e{0, pc.shape.d_a, pc.shape.s_b - pc.shape.s_a, pc.shape.d_b};
    const double hw = swept_half_width(g_.params().half_width, max_kappa(pc.shape), keep);
    for (const auto& o : obs) {
      FrenetObstacle r = o;
      r.s = relative_s(o.s, pc.shape.s_a, L);
      if (edge_blocked(e, r, hw, keep, nullptr, relative_s(s_c, pc.shape.s_a, L))) return true;
    }
  }
  return false;
}

double RoadGraphPlanner::max_kappa(const EdgeShape& e) const {
  constexpr int kSamples = 10;
  const double ds = (e.s_b - e.s_a) / kSamples;
  double kmax = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double s = e.s_a + (k + 0.5) * ds;
    kmax = std::max(kmax, std::abs(offset_curvature(line_.kappa(s), e.d(s), e.d1(s), e.d2(s))));
  }
  return kmax;
}

namespace {
constexpr double kInBandSlope = 0.05;  // m across per m along: 3°
}  // namespace

namespace {
// The nearest obstacle in the way of the car (s_c, d_c) going on at its offset, within the
// horizon, and how far ahead it is; null: none.
const FrenetObstacle* nearest_in_way(const std::vector<FrenetObstacle>& obs, double s_c, double d_c, double L, double hw,
                                     const SearchParams& keep, double horizon, double* ahead) {
  const FrenetObstacle* first = nullptr;
  for (const auto& o : obs) {
    const double r = relative_s(o.s, s_c, L);
    if (r <= 0 || r > horizon) continue;
    if (std::abs(o.d - d_c) >= o.radius + hw + keep.clearance) continue;
    if (!first || r < *ahead) { first = &o; *ahead = r; }
  }
  return first;
}
}  // namespace

// One emergency swerve's setting: the obstacle in the way (`first`, one of `obs`), the band at it
// (lo, hi), and where the lane change starts (s0), ends (s1) and the car is past the obstacle (s2).
struct RoadGraphPlanner::Swerve {
  const RoadGraphPlanner& pl;
  const std::vector<FrenetObstacle>& obs;
  const FrenetObstacle* first;
  const SearchParams& keep;
  double speed, d_c, L, hw;
  double lo, hi, s0, s1, s2;
  double need;  // the offset from the obstacle that passes it at keep_clearance

  std::vector<Piece> shape(double d_t) const {
    return std::vector<Piece>{{EdgeShape{s0 - pl.p_.behind, d_c, s0, d_c}, kNoNode},
                              {EdgeShape{s0, d_c, s1, d_t}, kNoNode},
                              {EdgeShape{s1, d_t, s2, d_t}, kNoNode}};
  }
  // Steerable: within the graph's curvature limit, and at the speed the car has at each point of
  // the lane change and the stretch past the obstacle while it brakes as hard as the grip its
  // bend leaves allows (the friction ellipse). Judged at the car's speed now for the whole of it,
  // a swerve in a bend near the car's lateral limit was never steerable, and the car passed
  // Monza's Lesmo pylon, hidden by the inner wall until 97 m ahead at 65 m/s, 0.44 m off.
  bool steerable(const std::vector<Piece>& ps) const {
    double v2 = speed * speed;
    for (std::size_t i = 1; i < ps.size(); ++i) {
      const EdgeShape& e = ps[i].shape;
      const int n = std::max(1, static_cast<int>(std::ceil((e.s_b - e.s_a) / 1.0)));
      const double ds = (e.s_b - e.s_a) / n;
      for (int k = 0; k < n; ++k) {
        const double s = e.s_a + (k + 0.5) * ds;
        const double kappa = std::abs(offset_curvature(pl.line_.kappa(s), e.d(s), e.d1(s), e.d2(s)));
        if (kappa > pl.g_.params().max_curvature) return false;
        if (keep.lateral_accel <= 0) continue;
        const double lat = kappa * v2 / keep.lateral_accel;
        if (lat > 1) return false;
        v2 = std::max(0.0, v2 - 2 * pl.p_.limits.a_decel * std::sqrt(1 - lat * lat) * ds);
      }
    }
    return true;
  }
  // The least gap between the car's swept side and the obstacles along the pieces: `first`
  // alone, or every other one.
  double least_gap(const std::vector<Piece>& ps, bool of_first) const {
    double least = 1e300;
    for (const Piece& pc : ps) {
      const EdgeShape e{0, pc.shape.d_a, pc.shape.s_b - pc.shape.s_a, pc.shape.d_b};
      const double w = swept_half_width(hw, pl.max_kappa(pc.shape), keep);
      for (const auto& o : obs) {
        if ((&o == first) != of_first) continue;
        FrenetObstacle r = o;
        r.s = relative_s(o.s, pc.shape.s_a, L);
        double gap = 1e300;
        edge_blocked(e, r, w, keep, &gap);
        least = std::min(least, gap);
      }
    }
    return least;
  }
  // The lane change at keep_clearance to the side with less sideways travel; empty: none.
  std::vector<Piece> at_keep_clearance(double* past) const {
    std::vector<Piece> best;
    double best_move = 1e300;
    for (const int side : {-1, +1}) {
      const double d_t = first->d + side * need;
      if (d_t < lo || d_t > hi || std::abs(d_t - d_c) >= best_move) continue;
      std::vector<Piece> ps = shape(d_t);
      if (!steerable(ps) || std::min(least_gap(ps, true), least_gap(ps, false)) < keep.clearance) continue;
      pl.append_in_band(ps, s2, d_t, pl.p_.search.horizon);
      best = std::move(ps);
      best_move = std::abs(d_t - d_c);
      *past = s2;
    }
    return best;
  }
  // The farthest offset toward `full` (within the band) that the car steers at its speed.
  double farthest_steerable(double full) const {
    double ok = d_c, bad = full;
    if (steerable(shape(full))) {
      ok = full;
    } else {
      for (int k = 0; k < 20; ++k) {
        const double mid = 0.5 * (ok + bad);
        (steerable(shape(mid)) ? ok : bad) = mid;
      }
    }
    return ok;
  }
  // The lane change that passes the obstacle farthest off, when that is farther than braking
  // straight on would pass it, clear of every other obstacle; empty: none.
  std::vector<Piece> least_harm(double* past, bool* short_of) const {
    std::vector<Piece> best;
    double best_gap = least_gap(shape(d_c), true);
    for (const int side : {-1, +1}) {
      const double full = std::clamp(first->d + side * need, lo, hi);
      if ((full - d_c) * side <= 0) continue;
      const double ok = farthest_steerable(full);
      std::vector<Piece> ps = shape(ok);
      const double gap = least_gap(ps, true);
      if (gap <= best_gap + 0.05 || least_gap(ps, false) < keep.clearance) continue;
      pl.append_in_band(ps, s2, ok, pl.p_.search.horizon);
      best = std::move(ps);
      best_gap = gap;
      *past = s2;
      *short_of = true;
    }
    return best;
  }
};

std::vector<RoadGraphPlanner::Piece> RoadGraphPlanner::emergency_swerve(double s_c, double d_c, double speed,
                                                                        const std::vector<FrenetObstacle>& obs,
                                                                        double* past, bool* short_of) const {
  *short_of = false;
  const double L = line_.length(), hw = g_.params().half_width;
  SearchParams keep = p_.search;
  keep.clearance = std::min(p_.keep_clearance, p_.search.clearance);
  double ahead = 0;
  const FrenetObstacle* first = nearest_in_way(obs, s_c, d_c, L, hw, keep, p_.search.horizon, &ahead);
  if (!first) return {};
  // Where the car's nose reaches the obstacle. (A car that could stop before it swerves too: one
  // stopped there has no lead-in sharp enough to go round, and would stand.)
  const double reach = ahead - p_.search.car_front - first->radius;
  if (reach < 5.0) return {};
  // The sides: the emergency band at the obstacle (the graph's band widened to swerve_edge_margin).
  const auto& Ly = g_.layers()[g_.layer_at_or_after(first->s)];
  const double step = g_.params().lateral_step, widen = std::max(0.0, g_.params().edge_margin - p_.swerve_edge_margin);
  const double lo = Ly.k0 * step - widen, hi = (Ly.k0 + static_cast<double>(Ly.count) - 1) * step + widen;
  const double s0 = s_c, s1 = s_c + reach, s2 = first->s + (first->s < s_c ? L : 0.0) + p_.search.car_rear + first->radius + 5;
  // The car's sweep beside the obstacle widens it by the bend it takes there: the line's, a
  // tenth more for the offset (a hairpin's 0.07 1/m sweeps the AV-21's nose 0.5 m wide; taken
  // straight, every swerve in one came out short of keep_clearance once its shape was checked).
  // The lane change's own bends are not known before its shape: that is checked after.
  double bend = 0;
  for (double s = s1 - 10; s <= s2; s += 1.0) bend = std::max(bend, std::abs(line_.kappa(s)));
  const double need = first->radius + swept_half_width(hw, 1.1 * bend, keep) + keep.clearance + 0.05;
  const Swerve sw{*this, obs, first, keep, speed, d_c, L, hw, lo, hi, s0, s1, s2, need};
  if (std::vector<Piece> best = sw.at_keep_clearance(past); !best.empty()) return best;
  // None at keep_clearance. A car that can stop before the obstacle does (the caller's stop);
  // one that cannot steers as far from it as it can while it brakes, when that passes it
  // farther than braking straight on would, clear of every other obstacle.
  const double brake = p_.limits.a_decel > 0 ? speed * speed / (2 * p_.limits.a_decel) : 1e300;
  if (brake <= reach) return {};
  return sw.least_harm(past, short_of);
}

void RoadGraphPlanner::append_in_band(std::vector<Piece>& pieces, double s_a, double d_a, double length) const {
  const double L = line_.length(), step = g_.params().lateral_step;
  const int nl = static_cast<int>(g_.layers().size());
  // The layers ahead: where each stands (s unwrapped like the pieces) and its band of nodes.
  struct Band {
    double s, lo, hi;
  };
  std::vector<Band> ahead;
  double s = s_a;
  int layer = g_.layer_at_or_after(s_a + 1e-6);
  for (int n = 0; n < nl && s < s_a + length; ++n) {
    const auto& Ly = g_.layers()[layer];
    double h = Ly.s - s;
    h -= std::floor(h / L) * L;  // the next layer, however far round the loop
    if (h < 1e-6) h += L;
    s += h;
    const double lo = Ly.k0 * step;
    ahead.push_back({s, lo, std::max(lo, (Ly.k0 + static_cast<double>(Ly.count) - 1) * step)});
    layer = (layer + 1) % nl;
  }
  if (ahead.empty()) return;
  // A car placed beyond the track's edge is not there: its estimate is off, and the line's shape
  // (the parallel) is the best guess of the road ahead of it. Steered into the band at even 3°,
  // a car 31 m off on a drifted estimate went 3° into the wall (graph.ims_race_60_localization_comes_back).
  const Band& first = ahead.front();
  const double outside = d_a > first.hi ? d_a - first.hi : d_a < first.lo ? first.lo - d_a : 0.0;
  const bool on_track = outside <= g_.params().edge_margin + g_.params().half_width;
  // Backward: the band as it must already be met, at the slope, before it narrows.
  for (std::size_t i = ahead.size() - 1; i-- > 0;) {
    const double h = ahead[i + 1].s - ahead[i].s;
    ahead[i].hi = std::min(ahead[i].hi, ahead[i + 1].hi + kInBandSlope * h);
    ahead[i].lo = std::max(ahead[i].lo, ahead[i + 1].lo - kInBandSlope * h);
  }
  double from = s_a, d = d_a;
  for (const Band& b : ahead) {
    double d_b = d_a;
    if (on_track) {
      const double turn = kInBandSlope * (b.s - from);
      d_b = std::clamp(std::clamp(d_a, b.lo, std::max(b.lo, b.hi)), d - turn, d + turn);
    }
    pieces.push_back({EdgeShape{from, d, b.s, d_b}, kNoNode});
    from = b.s;
    d = d_b;
  }
}

std::vector<std::pair<std::uint32_t, double>> RoadGraphPlanner::lead_ins(double s_c, double d_c, double commit,
                                                                         const std::vector<FrenetObstacle>& obs,
                                                                         const SearchParams& sp) const {
  const double L = line_.length();
  const int layer = g_.layer_at_or_after(s_c + commit);
  const auto& Ly = g_.layers()[layer];
  double h = Ly.s - s_c;
  if (h <= 0) h += L;
  std::vector<std::pair<std::uint32_t, double>> out;
  for (std::uint32_t n = Ly.first_node; n < Ly.first_node + Ly.count; ++n) {
    const EdgeShape e{-p_.behind, d_c, h, g_.node_d(n)};  // s relative to the car
    // Its bends first: the body's sweep widens the car by them. (The steering check below takes
    // the car's speed now for the whole lead-in, stricter than the search's edges, which are
    // judged by the speed the car can brake to by then.)
    constexpr int kSamples = 10;
    const double ds = (e.s_b - e.s_a) / kSamples;
    double cost = 0, kmax = 0;
    for (int k = 0; k < kSamples; ++k) {
      const double s = e.s_a + (k + 0.5) * ds, d = e.d(s), d1 = e.d1(s), kr = line_.kappa(s_c + s);
      const double q = 1 - kr * d, dl = std::sqrt(q * q + d1 * d1) * ds;
      const double kappa = offset_curvature(kr, d, d1, e.d2(s));
      cost += sp.k_length * dl + sp.k_curvature * kappa * kappa * dl + sp.k_deviation * std::abs(d) * ds;
      kmax = std::max(kmax, std::abs(kappa));
    }
    const double hw = swept_half_width(g_.params().half_width, kmax, sp);
    bool ok = true;
    for (const auto& o : obs) {
      FrenetObstacle r = o;
      r.s = relative_s(o.s, s_c, L);
      double gap;
      // From the car on; one that stands beside the obstacle nearer than the clearance (it
      // stopped there) may leave by any lead-in that takes it no nearer than it is.
      SearchParams near = sp;
      near.clearance = std::min(sp.clearance, gap_beside(r, d_c, hw, sp) - 0.01);
      if (edge_blocked(e, r, hw, near, &gap, 0.0)) { ok = false; break; }
      if (gap < sp.soft_clearance) cost += sp.k_proximity * (sp.soft_clearance - gap) * (sp.soft_clearance - gap);
    }
    if (!ok) continue;
    const bool steerable = kmax <= g_.params().max_curvature &&
                           (sp.lateral_accel <= 0 || kmax * reachable_speed2(sp, 0) <= sp.lateral_accel);
    if (steerable || std::abs(g_.node_d(n) - d_c) < g_.params().lateral_step) out.emplace_back(n, cost);
  }
  return out;
}

double RoadGraphPlanner::stop_at(const std::vector<Piece>& pieces, const std::vector<FrenetObstacle>& obs, double s_c) const {
  const double L = line_.length();
  double stop = pieces.back().shape.s_b;
  if (obs.empty()) return stop;
  for (const Piece& pc : pieces) {
    const EdgeShape e{0, pc.shape.d_a, pc.shape.s_b - pc.shape.s_a, pc.shape.d_b};
    const double hw = swept_half_width(g_.params().half_width, max_kappa(pc.shape), p_.search);
    for (const auto& o : obs) {
      FrenetObstacle r = o;
      r.s = relative_s(o.s, pc.shape.s_a, L);
      if (edge_blocked(e, r, hw, p_.search, nullptr, relative_s(s_c, pc.shape.s_a, L)))
        stop = std::min(stop, pc.shape.s_a + r.s - p_.search.car_front - r.radius - p_.search.clearance);
    }
  }
  return stop;
}

std::vector<FrenetObstacle> RoadGraphPlanner::confirmed_obstacles(double s_c) const {
  std::vector<FrenetObstacle> obs;
  for (const MapObstacle& m : memory_) {
    if (m.seen < p_.confirmations) continue;
    const Eigen::Vector2d q = line_.to_frenet(m.x, m.y, s_c);
    if (std::isfinite(q.x()) && std::abs(q.y()) < 1000) obs.push_back({q.x(), q.y(), m.radius});
  }
  return obs;
}

std::vector<RoadGraphPlanner::Piece> RoadGraphPlanner::kept_pieces(double s_c, double d_c, double commit, bool* on_it) const {
  const double L = line_.length();
  std::vector<Piece> kept;
  for (const Piece& pc : pieces_) {
    const double ra = relative_s(pc.shape.s_a, s_c, L), rb = ra + (pc.shape.s_b - pc.shape.s_a);
    if (rb < 0) continue;
    if (ra <= 0) *on_it = std::abs(pc.shape.d(pc.shape.s_a - ra) - d_c) <= p_.rejoin;
    kept.push_back(pc);
    if (rb >= commit && !stopping_) break;
  }
  return kept;
}

Plan RoadGraphPlanner::search_from_car(double s_c, double d_c, double commit, const std::vector<FrenetObstacle>& obs,
                                       SearchParams sp) {
  Plan fresh;
  const double clearances[2] = {p_.search.clearance, std::min(p_.keep_clearance, p_.search.clearance)};
  for (int c = 0; c < 2 && !fresh.found; ++c) {
    if (c == 1 && !(clearances[1] < clearances[0])) break;
    sp.clearance = clearances[c];
    for (double reach = commit;; reach = std::max(p_.commit_min, reach - 10)) {
      sp.ahead = reach;
      fresh = search_.plan(lead_ins(s_c, d_c, reach, obs, sp), obs, sp);
      out_.edges_relaxed += fresh.edges_relaxed;
      if (fresh.found || reach <= p_.commit_min) break;
    }
    // A slow car beside the band (it stopped there) may have no lead-in sharp enough to the
    // layer at the commitment distance, but one to a layer farther on: there, its lead-in
    // bends gently back into the band (lead_ins keeps it clear of the obstacles).
    for (double reach = commit + 10; !fresh.found && reach <= commit + p_.rejoin_reach; reach += 10) {
      sp.ahead = reach;
      fresh = search_.plan(lead_ins(s_c, d_c, reach, obs, sp), obs, sp);
      out_.edges_relaxed += fresh.edges_relaxed;
    }
  }
  return fresh;
}

void RoadGraphPlanner::follow_route(const Plan& plan, std::vector<Piece> pieces, double speed) {
  const double L = line_.length();
  for (std::size_t i = 1; i < plan.nodes.size(); ++i) {
    const std::uint32_t a = plan.nodes[i - 1], b = plan.nodes[i];
    double h = g_.node_s(b) - g_.node_s(a);
    if (h <= 0) h += L;
    const double sa = pieces.back().shape.s_b;
    pieces.push_back({EdgeShape{sa, g_.node_d(a), sa + h, g_.node_d(b)}, b});
  }
  pieces_ = std::move(pieces);
  stopping_ = false;
  make_path(speed, false, 0);
}

void RoadGraphPlanner::brake_to_stop(const std::vector<Piece>& kept, bool usable, double s_c, double d_c, double commit,
                                     const std::vector<FrenetObstacle>& obs, double speed) {
  if (!(stopping_ && usable)) {
    if (usable) {
      pieces_ = kept;
    } else {
      pieces_ = {{EdgeShape{s_c - p_.behind, d_c, s_c + commit, d_c}, kNoNode}};
      out_.restarted = true;
    }
    // On along the line at the same offset (within the track) over the horizon: the car stops
    // before the blockage, not at the end of its commitment.
    const EdgeShape end = pieces_.back().shape;
    append_in_band(pieces_, end.s_b, end.d_b, p_.search.horizon);
  } else {
    pieces_ = kept;
  }
  stopping_ = true;
  make_path(speed, true, stop_at(pieces_, obs, s_c));
}

const PlannedPath& RoadGraphPlanner::plan(double x, double y, double speed) {
  const double L = line_.length();
  out_ = PlannedPath{};
  const Eigen::Vector2d f = line_.to_frenet(x, y, hint_s_);
  const double s_c = f.x(), d_c = f.y();
  // A pose nowhere near the line (a corrupt estimate): no path at all, rather than one built on it.
  if (!(std::isfinite(s_c) && std::abs(d_c) < 1000)) return out_;
  hint_s_ = s_c;
  if (!(speed >= 0 && speed < 1000)) speed = 0;
  const std::vector<FrenetObstacle> obs = confirmed_obstacles(s_c);
  // What stays of the last plan: pieces not yet behind the car, up to the commitment point (all
  // of them while stopping: the stop point stays where it was).
  const double commit = std::max(p_.commit_min, p_.commit_time * speed);
  bool on_it = false;
  const std::vector<Piece> kept = kept_pieces(s_c, d_c, commit, &on_it);
  const bool usable = on_it && !kept.empty() && !committed_blocked(kept, obs, s_c);
  const bool reaches = usable && relative_s(kept.back().shape.s_b, s_c, L) >= commit && kept.back().end != kNoNode;
  Plan plan;
  SearchParams sp = p_.search;  // the car's speed, for the curvature its speed allows
  sp.speed = speed;
  if (reaches && !stopping_) {
    sp.ahead = relative_s(kept.back().shape.s_b, s_c, L);
    plan = search_.plan(kept.back().end, obs, sp);
    out_.edges_relaxed += plan.edges_relaxed;
  }
  std::vector<Piece> pieces = kept;
  if (!plan.found) {
    // Start afresh from the car: every node of the layer at the commitment distance that a
    // lead-in reaches without meeting an obstacle, the lead-in's cost counted.
    // When an obstacle seen late leaves no way round at the commitment distance, nearer layers
    // are tried (a sharper lead-in; the speeds follow its bends), down to commit_min.
    // With none at the clearance, once more at keep_clearance before the car stops.
    if (Plan fresh = search_from_car(s_c, d_c, commit, obs, sp); fresh.found) {
      plan = std::move(fresh);
      const std::uint32_t first = plan.nodes.front();
      double h = g_.node_s(first) - s_c;
      if (h <= 0) h += L;
      pieces = {{EdgeShape{s_c - p_.behind, d_c, s_c + h, g_.node_d(first)}, first}};
      out_.restarted = true;
    }
  }
  out_.route_found = plan.found;
  if (plan.found) {
    follow_route(plan, std::move(pieces), speed);
    return out_;
  }
  // No route: stop. On what the car is committed to while it is usable (it then stays put),
  // else on a straight line at the car's offset.
  // An obstacle in the car's way with no route round it in the graph: swerve past it, braking,
  // nearer the edge than the graph goes.
  double past = 0;
  bool short_of = false;
  if (std::vector<Piece> swerve = emergency_swerve(s_c, d_c, speed, obs, &past, &short_of); !swerve.empty()) {
    pieces_ = std::move(swerve);
    out_.restarted = true;
    out_.swerve = true;
    out_.swerve_short = short_of;
    stopping_ = false;  // next cycle: a route if one opens, else the swerve again from where the car is
    make_path(speed, true, past);
    return out_;
  }
  brake_to_stop(kept, usable, s_c, d_c, commit, obs, speed);
  return out_;
}

void RoadGraphPlanner::make_path(double speed, bool stop, double stop_s) {
  // Points along the pieces (all of them: past a stop the speeds are zero, and the tracker keeps
  // a path to steer along), then speeds within the line's profile and the
  // path's bends — braking from the car's speed to zero at the stop.
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
    // Past the stop the path goes on (the tracker keeps steering along it) at speed zero.
    // (Zero from the last point before the stop: the profile reaches zero at a point, not between.)
    cap[i] = stop && q.s > stop_s - p_.path_step ? 0.0 : line_.interpolate(ref_speed_, q.s);
    if (i + 1 < n) ds[i] = std::max(1e-3, std::hypot(out_.points[i + 1].x - q.x, out_.points[i + 1].y - q.y));
  }
  out_.speed = stop ? speed_profile(ds, kappa, p_.limits, false, speed, 0.0, &cap)
                    : speed_profile(ds, kappa, p_.limits, false, -1, -1, &cap);
}

}  // namespace brickyard::planning
