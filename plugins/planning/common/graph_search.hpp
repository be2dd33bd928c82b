#pragma once
// The online half of the road-graph planner: the cheapest path through the lattice from a start
// node over a horizon, around obstacles. Framework-free.
//
// The layers are ordered along s, so this is dynamic programming over a DAG: each layer's nodes
// relax their edges in turn, and every edge is looked at once. An edge costs
//   f + g = k_length·l + k_curvature·∫κ² dl + k_deviation·∫|d| ds + k_proximity·Σ (soft − gap)²₊
// (travel, curvature and distance from the racing line as in the paper's g, with the obstacle
// term as a penalty for passing nearer than soft_clearance); an edge on which the car would come
// nearer than `clearance` to an obstacle is removed. Paths end anywhere past the horizon; the
// ends are made comparable by costing the rest of the way to a common s as a parallel to the line.
#include "road_graph.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace brickyard::planning {

struct FrenetObstacle {
  double s = 0, d = 0;  // on the racing line's frame, m
  double radius = 0.5;  // m
};

struct SearchParams {
  double horizon = 300;         // m of line ahead of the start node
  double clearance = 1.5;       // m between the car's side and an obstacle, at least
  double soft_clearance = 4.0;  // m: nearer than this costs k_proximity per m² short
  // The car's length around its reference point (base_link, the rear axle). These defaults serve
  // the unit tests and benchmarks; planning.road_graph sets both from the vehicle file.
  double car_front = 4.0;       // m of car ahead of base_link
  double car_rear = 1.0;        // m behind it
  double k_length = 1.0;
  double k_curvature = 2e4;     // per 1/m of ∫κ² dl
  double k_deviation = 0.05;    // per m² of ∫|d| ds
  double k_proximity = 10;      // per m² short of soft_clearance
  // The car's speed limits the curvature: with lateral_accel > 0, an edge that leaves
  // the line's offset (a lane change) is taken only when the car, braking at `brake` from `speed`
  // over the `ahead` metres to the start node and on to the edge, can be slow enough for its
  // sharpest point: max κ · v² <= lateral_accel. 0: off (the graph's max_curvature alone).
  double lateral_accel = 0;     // m/s^2
  double brake = 10;            // m/s^2
  double speed = 0;             // m/s, the car's
  double ahead = 0;             // m from the car to the start node
};

// The lowest speed squared the car can have `x` metres on, braking at p.brake from p.speed.
inline double reachable_speed2(const SearchParams& p, double x) {
  const double v2 = p.speed * p.speed - 2 * p.brake * (x > 0 ? x : 0.0);
  return v2 > 0 ? v2 : 0.0;
}

// The half width the car's body sweeps on a path of curvature kappa: its front corners,
// car_front ahead of base_link (which runs on the path), stand about car_front² |κ| / 2 outside
// the arc. In a hairpin (κ 0.08 1/m) a 4 m nose sweeps 0.64 m: a plan that passed a pylon 1 m
// off in the line's frame brought the car's corner within 0.47 m of it.
inline double swept_half_width(double half_width, double kappa, const SearchParams& p) {
  const double k = kappa < 0 ? -kappa : kappa;
  return half_width + 0.5 * p.car_front * p.car_front * (k < 1.0 ? k : 1.0);  // NaN: the straight car
}

struct Plan {
  bool found = false;
  std::vector<std::uint32_t> nodes;  // start first
  double cost = 0;
  std::size_t edges_relaxed = 0;
};

// An obstacle's place relative to a start at s0: along-line distance in (-length/2, length/2].
double relative_s(double s, double s0, double length);

// Whether the car following the edge from (rel_a, d_a) to (rel_b, d_b) comes nearer than the
// clearance to the obstacle (its s relative to the same origin); `side_gap` gets the least gap.
// `from`: where the car's reference point is now, on the edge (the part before it is driven).
bool edge_blocked(const EdgeShape& e, const FrenetObstacle& o, double half_width, const SearchParams& p,
                  double* side_gap = nullptr, double from = -1e300);

class GraphSearch {
 public:
  explicit GraphSearch(const RoadGraph& g);
  // Obstacles' s are map-frame s on the line (not relative).
  Plan plan(std::uint32_t start, const std::vector<FrenetObstacle>& obstacles, const SearchParams& p) {
    return plan({{start, 0.0}}, obstacles, p);
  }
  // From several start nodes of one layer, each with a cost already paid to reach it (the
  // planner's lead-ins from the car); the plan begins at the start it goes through.
  Plan plan(const std::vector<std::pair<std::uint32_t, double>>& starts, const std::vector<FrenetObstacle>& obstacles,
            const SearchParams& p);

 private:
  struct Frame;
  // The starts of the start node's layer l0, each once, at their costs.
  void seed_starts(const std::vector<std::pair<std::uint32_t, double>>& starts, int l0);
  // The DAG pass: layer by layer from the start's up to the horizon, every reached node's edges.
  void relax_layers(const Frame& fr, const std::vector<FrenetObstacle>& near, const SearchParams& p, Plan& out);
  void relax_node(const Frame& fr, std::uint32_t n, double ra, const std::vector<FrenetObstacle>& near, const SearchParams& p,
                  Plan& out);
  // Adds to `c` the proximity cost of the obstacles beside the edge; false: one blocks it.
  bool add_proximity_cost(const EdgeShape& shape, const RoadGraph::Edge& e, double hw, const SearchParams& p, double& c) const;
  // The cheapest node past the horizon and its cost on to a common end; node ~0u: none.
  std::pair<std::uint32_t, double> cheapest_end(const Frame& fr, const SearchParams& p) const;

  const RoadGraph& g_;
  std::vector<double> cost_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> touched_;
  std::vector<FrenetObstacle> beside_;  // near the edges being relaxed
};

}  // namespace brickyard::planning
