#pragma once
// planning.road_graph's work from configure to the summary, framework-free: the graph's and the
// planner's parameters for the car, a graph file checked against what this node would build, the
// line, the graph and the planner once the map is known, and each cycle's detections, plan and
// bookkeeping (the "no route" episodes, the counts the summary reports, the lattice drawn round
// the obstacles met). The plugin converts the messages.
#include "follow.hpp"
#include "line_setup.hpp"
#include "plan_frames.hpp"
#include "road_graph.hpp"
#include "road_graph_planner.hpp"

#include "track/track.hpp"
#include "vehicle/vehicle.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::planning {

// What the graph says about the car, the obstacles, the graph and the planner.
struct RoadGraphSettings {
  // The car's size: the vehicle file's unless the graph overrides it (NaN: off).
  std::optional<double> half_width, car_front, car_rear;
  double obstacle_edge_band = 1.0;
  double obstacle_place_sigmas = 2.0;
  bool car_curvature = false;   // curvature_limit car: the graph's edges and the search from the car's steering and speed
  double steer_margin = 0.8;
  RoadGraphParams graph;
  PlannerParams planner;
  FollowParams follow;
};

// The settings with the car applied.
struct RoadGraphConfig {
  RoadGraphParams graph;
  PlannerParams planner;
  FollowParams follow;
  double edge_band = 1.0, place_sigmas = 2.0;  // a detection's placement_band
};

// The car's size unless the settings override it, the line's speed limits (`limits`: as the
// racing line's profile, so the two planners agree on a clear track) and, with car_curvature, the
// car's tightest turn and the lateral grip its speed leaves (graph_search.hpp).
RoadGraphConfig road_graph_config(const RoadGraphSettings& s, const vehicle::Vehicle& car, const VehicleLimits& limits);

// A problem the node reports as it is: a graph file that does not fit, or the line or the graph
// that could not be made for the map.
struct RoadGraphInputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The graph file at `path` (found) loaded and checked: built with `graph` and for the racing line
// file and edge margin of `src`. Throws RoadGraphInputError naming the file.
std::unique_ptr<RoadGraph> load_graph_file(const std::string& path, const LineSource& src, const RoadGraphParams& graph);

// One cycle's plan as the Path carries it, and the warning to log first (empty: none).
struct CyclePlan {
  PathGeometry path;
  std::vector<double> speed;  // m/s per point
  std::string warning;        // once per episode without a route: which obstacles closed the road
};

// The lattice's nodes (map frame) from 150 m before to 100 m past every obstacle met.
struct LatticeDrawing {
  std::vector<double> x, y;
};

class RoadGraphRun {
 public:
  // `loaded`: a graph file's graph (load_graph_file; null: built from the map at start) and its path.
  RoadGraphRun(LineSource src, RoadGraphConfig config, std::unique_ptr<RoadGraph> loaded, std::string graph_file);
  RoadGraphRun(const RoadGraphRun&) = delete;  // the planner holds the line and the graph
  RoadGraphRun& operator=(const RoadGraphRun&) = delete;

  bool started() const { return planner_ != nullptr; }
  // The racing line, the graph and the planner for the map's track. Returns the line to log.
  // Throws RoadGraphInputError naming the line when one of them cannot be made.
  std::string start(track::TrackGeometry map);

  // The cars the tracker follows now (map frame): their detections are not obstacles, and the
  // plan's speeds follow the first in its way (follow.hpp).
  void set_cars(std::vector<MovingCar> cars) { cars_ = std::move(cars); }
  // One obstacle list (vehicle frame) placed with the pose of its stamp: what can stand in the
  // car's way (and is no moving car's) joins `seen`, the rest is counted off the track.
  void place(const StampedPose& at, const std::vector<Detection>& list, std::vector<MapObstacle>& seen);
  // The cycle's detections remembered; the layers round the obstacles noted for the drawing.
  void observe(const std::vector<MapObstacle>& seen, std::int64_t now_ns);
  // A plan from the car's reference point and speed; none when the pose is not finite or sane, or
  // the plan has fewer than two points.
  std::optional<CyclePlan> plan(double x, double y, double speed);

  // The summary's numbers, in the order they are reported; `plans`: the paths published.
  std::vector<std::pair<std::string, double>> metrics(std::uint32_t plans) const;
  LatticeDrawing lattice_near_obstacles() const;  // empty without a graph

 private:
  // Once per episode without a route: which obstacles closed the road (the car brakes for them).
  std::string no_route_warning(const PlannedPath& plan, double x, double y) const;
  void count(const PlannedPath& plan);
  void follow_cars(const PlannedPath& plan, double x, double y, double our_speed, std::vector<double>& speed);

  LineSource src_;
  RoadGraphConfig config_;
  std::string line_file_, graph_file_;
  std::unique_ptr<track::Track> track_;  // the map's, once it came
  Reference line_ready_;
  std::unique_ptr<RoadGraph> loaded_, graph_;
  std::unique_ptr<RoadGraphPlanner> planner_;
  double planned_lap_s_ = 0, max_offset_ = 0;
  bool stopping_ = false;
  std::size_t blocked_ = 0, restarts_ = 0, swerves_ = 0, obstacles_max_ = 0, planned_around_max_ = 0, off_track_ = 0;
  std::vector<MovingCar> cars_;
  std::size_t following_ = 0, car_detections_ = 0;  // plans whose speeds followed a car; detections left to the cars
  double min_follow_gap_ = std::numeric_limits<double>::infinity();
  std::set<int> shown_layers_;
};

}  // namespace brickyard::planning
