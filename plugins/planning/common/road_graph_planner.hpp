#pragma once
// The replanning loop of planning.road_graph, framework-free: obstacles remembered in the map
// frame, the part of the last plan the car is committed to, a graph search from its end, and the
// path with its speeds.
//
// Commitment: the car keeps the last plan up to the first node at least max(commit_min,
// commit_time · v) ahead, and the search starts there, so successive plans join without a jump
// (the paper replans at 20 Hz). The plan restarts — from every node of the layer at the
// commitment distance that a smooth lead-in from the car reaches without meeting an obstacle,
// the lead-in's cost counted as an edge's — when the car is off the committed part by more than
// `rejoin` metres, an obstacle now blocks it, or no route goes on from its end.
//
// No route at all: the car stops. The path is the part it is committed to (or, when that is
// blocked or gone, a straight line at its offset) and on at the same offset from the line over
// the horizon, its speeds braking from the car's to zero where the car would come within the
// clearance of the first obstacle in its way (and zero beyond).
// That stop point stays put from cycle to cycle (it does not move ahead with the car) until a
// route opens.
#include "graph_search.hpp"
#include "road_graph.hpp"
#include "motion/speed_profile.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::planning {

using motion::VehicleLimits;
using motion::closed_lap_time_gradient;
using motion::profile_time;
using motion::speed_profile;

struct PlannerParams {
  SearchParams search;
  VehicleLimits limits;           // for the path's own curvature; ref_speed caps it besides
  double commit_time = 1.0;       // s
  double commit_min = 15;         // m
  double rejoin = 2.0;            // m off the committed path before it is dropped
  double path_step = 2.0;         // m between path points
  double behind = 3.0;            // m of path behind the car (the tracker projects the car on it)
  // With no route from the layer at the commitment distance: lead-ins to layers up to this much
  // farther are tried (a car that stopped beside the band rejoins it gently).
  double rejoin_reach = 50;       // m
  double obstacle_memory = 2.0;   // s an obstacle is kept after it was last seen
  double merge_distance = 1.5;    // m: a detection this near a remembered obstacle is that one
  // On: a remembered obstacle's place is its detections fused, each weighted by the spread of its
  // own place (a far one's, from the heading's error, is large), the fused place's variance
  // growing by obstacle_drift² (m²/s) a second so a moving obstacle is followed. Off: each
  // detection replaces the place. Fused, a pylon 100 m ahead no longer jumps ±0.5 m sideways with
  // the estimate's heading, and the plan round it no longer flips sides at 70 m/s (Monza's Roggia).
  // Its weights need each detection placed by the estimate at its stamp (interpolated, not the
  // nearest: 4 ms off is 0.3 m at 80 m/s); with the nearest it put that Roggia pylon's car into
  // the wall (docs/planning.md).
  bool obstacle_fusion = true;
  double obstacle_drift = 0.5;
  int confirmations = 3;          // frames an obstacle must be seen in before it is planned around:
                                  // one frame's false detection must not close the road
  // m between the car's side and an obstacle below which a plan already made is dropped, and at
  // which a search that finds no way at search.clearance tries again before the car stops. A
  // plan made at the full clearance is kept while the obstacle's place, detection by detection,
  // moves by centimetres: without this margin a swerve made at exactly the clearance flickered
  // between planned and blocked, and the car, too near by then for any other way, braked.
  double keep_clearance = 1.0;
  // m between the car's side and the track's edge that an emergency swerve may use (the graph's
  // nodes keep edge_margin): with no route at any clearance and an obstacle in the car's way,
  // the car swerves past it braking, nearer the edge than the graph goes (Monza's 8.2 m straight
  // has no node beside a pylon on its centre line).
  double swerve_edge_margin = 0.5;
};

struct MapObstacle {
  double x = 0, y = 0, radius = 0.5;  // map frame, m
  std::int64_t seen_ns = 0;
  int seen = 0;                       // frames it was detected in
  double variance = 0.01;             // m², of the place along each axis
};

struct PlannedPath {
  std::vector<PathSample> points;  // s on the line (not wrapped), d, x, y, curvature
  std::vector<double> speed;       // m/s per point
  bool route_found = false;        // false: every route was blocked; the path brakes to a stop
  bool restarted = false;          // the committed part was dropped this cycle
  bool swerve = false;             // no route: an emergency swerve past the obstacle, braking
  bool swerve_short = false;       // ... one short of keep_clearance: the car could neither stop
                                   // before the obstacle nor steer that far at its speed
  std::size_t edges_relaxed = 0;
};

class RoadGraphPlanner {
 public:
  // ref_speed: one speed per point of `line` (the racing line's profile), the cap everywhere.
  RoadGraphPlanner(const RoadGraph& graph, const RefLine& line, std::vector<double> ref_speed, PlannerParams p);

  // New detections (map frame) of one frame at now_ns: merged into the remembered ones; old ones
  // forgotten. Only those seen in `confirmations` frames are planned around.
  void observe(const std::vector<MapObstacle>& seen, std::int64_t now_ns);
  const std::vector<MapObstacle>& obstacles() const { return memory_; }  // confirmed or not

  // A new plan from the car's reference point and speed.
  const PlannedPath& plan(double x, double y, double speed);

 private:
  struct Piece {
    EdgeShape shape;       // s on the line, s_b may run past the line's length
    std::uint32_t end;     // the node it ends at
  };
  // Whether an obstacle blocks the pieces from the car (at s_c on the line) on: an obstacle the
  // car has passed blocks nothing (with the part of the path behind the car counted, a car that
  // passed one near and stopped could never start again).
  bool committed_blocked(const std::vector<Piece>& pieces, const std::vector<FrenetObstacle>& obs, double s_c) const;
  // Lead-ins from the car (s_c, d_c) to the reachable nodes of the layer at the commitment
  // distance, each with its cost (as an edge's, in the search's terms); at the car's speed
  // (sp.speed), a lead-in sharper than sp.lateral_accel allows is not one.
  std::vector<std::pair<std::uint32_t, double>> lead_ins(double s_c, double d_c, double commit,
                                                         const std::vector<FrenetObstacle>& obs, const SearchParams& sp) const;
  // Where a car on these pieces must stop (s on the line, unwrapped like the pieces): before the
  // first obstacle that blocks them, or at their end.
  double stop_at(const std::vector<Piece>& pieces, const std::vector<FrenetObstacle>& obs, double s_c) const;
  // With no route: from (s_a, d_a) on over `length` metres, layer by layer at the offset d_a
  // brought within each layer's nodes (inside the track), at a slope of at most 3° and early
  // enough for where the band narrows: a parallel to the line would leave the track where the
  // line runs along the other edge. A start beyond the track's edge (a drifted estimate) keeps
  // the parallel.
  void append_in_band(std::vector<Piece>& pieces, double s_a, double d_a, double length) const;
  // The largest |κ| along a piece (s on the line), from ten samples as the graph's edges.
  double max_kappa(const EdgeShape& e) const;
  // With no route: a lane change from the car (s_c, d_c) past the nearest obstacle in its way,
  // to the side it reaches with less sideways travel, at keep_clearance and within
  // swerve_edge_margin of the track's edge; steerable at the car's speed and clear of every
  // obstacle; `past`: where the car is past the obstacle. Empty when there is none.
  // With none, and a car that cannot stop before the obstacle: the lane change that passes it
  // farthest off within the car's lateral limit and the band (`*short_of` set), when that is
  // farther than braking straight on would pass it — the least harm.
  std::vector<Piece> emergency_swerve(double s_c, double d_c, double speed, const std::vector<FrenetObstacle>& obs,
                                      double* past, bool* short_of) const;
  struct Swerve;  // one emergency swerve's setting and its candidate lane changes
  // The remembered obstacles seen in `confirmations` frames, on the line's frame near s_c.
  std::vector<FrenetObstacle> confirmed_obstacles(double s_c) const;
  // What stays of the last plan: pieces not yet behind the car, up to the commitment point (all
  // of them while stopping); `on_it`: the car is within `rejoin` of the piece it is on.
  std::vector<Piece> kept_pieces(double s_c, double d_c, double commit, bool* on_it) const;
  // A search from lead-ins from the car: to the layer at the commitment distance, then nearer
  // ones down to commit_min, then farther ones up to rejoin_reach; at the search's clearance,
  // then at keep_clearance.
  Plan search_from_car(double s_c, double d_c, double commit, const std::vector<FrenetObstacle>& obs, SearchParams sp);
  // The plan's nodes as pieces after `pieces`, and the path along them.
  void follow_route(const Plan& plan, std::vector<Piece> pieces, double speed);
  // No route and no swerve: the path that brakes to a stop before the first obstacle in the way.
  void brake_to_stop(const std::vector<Piece>& kept, bool usable, double s_c, double d_c, double commit,
                     const std::vector<FrenetObstacle>& obs, double speed);
  void make_path(double speed, bool stop, double stop_s);
  const RoadGraph& g_;
  const RefLine& line_;
  std::vector<double> ref_speed_;
  PlannerParams p_;
  GraphSearch search_;
  std::vector<MapObstacle> memory_;
  std::vector<Piece> pieces_;
  double hint_s_ = -1;
  bool stopping_ = false;  // the last plan found no route: its pieces end at a fixed stop
  PlannedPath out_;
};

}  // namespace brickyard::planning
