// planning.road_graph: the paper's obstacle-avoiding planner. A lattice along the racing line
// (built from the map at start, or loaded from a file `brickyard-plan graph` wrote) is searched
// at rate_hz from the car's estimate around the obstacles perception reports; the Path it
// publishes runs horizon metres ahead with speeds. Same ports and line parameters as
// planning.racing_line, so the two swap by the plugin's name. Algorithms:
// ../common/road_graph_run.hpp; the frames and the Path's geometry: ../common/plan_frames.hpp.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/TrackedObjectList.h>
#include <brickyard/plugin.hpp>

#include "planning/common/road_graph_run.hpp"
#include "map_msg.hpp"
#include "newest.hpp"
#include "params.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::planning;

struct Ports {
  Input<msgs::TrackMap> map;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::ObstacleList> obstacles;
  Input<msgs::TrackedObjectList> tracks;
  Output<msgs::Path> path;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("map", &Ports::map).doc("the track: the graph's room and the line's edge margin (must be wired)").optional().depth(1);
  b.input("estimate", &Ports::estimate).doc("where the car is (base_link, map frame)").optional().depth(64);
  b.input("obstacles", &Ports::obstacles).doc("obstacles in the vehicle frame, placed with the estimate of their stamp").optional();
  b.input("tracks", &Ports::tracks).doc("moving cars (a tracker's): followed, not planned round as obstacles (optional)").optional().depth(1);
  b.output("path", &Ports::path).doc("horizon m of path from just behind the car, with speeds (open)");
  return b;
}

std::vector<Detection> detections(const msgs::ObstacleList& list) {
  std::vector<Detection> out;
  for (const auto& o : list.obstacles()) out.push_back({o.x(), o.y(), o.size_x(), o.size_y()});
  return out;
}

std::vector<MovingCar> moving_cars(const msgs::TrackedObjectList& list) {
  std::vector<MovingCar> out;
  for (const auto& o : list.objects()) out.push_back({o.x(), o.y(), o.vx(), o.vy(), o.speed_sigma(), o.size_x(), o.size_y()});
  return out;
}

class RoadGraphNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("planning.road_graph", "1.0.0")
        .describe("obstacle avoidance on a road graph (Frenet lattice) along the racing line; a Path with speeds, replanned at rate_hz")
        .with_ports(ports())
        .plays(roles::planner)
        .parameters(bindings())
        .periodic("rate_hz")
        .step_deadline("step_deadline_s")
        .check(&check);
  }

  // At validation, the files the parameters name read and checked as configure will.
  static void check(const CheckView& v) { read_inputs(v, bindings().read(v.params())); }

  void configure(Context& ctx) override {
    RoadGraphInputs in = read_inputs(ctx, bindings().read(ctx.params()));
    run_.emplace(std::move(in.line), in.config, std::move(in.graph), in.graph_file);
    io_ = ports().connect(ctx);
    // The line is kept inside the track's edges as the graph was built: the map is needed even
    // with a graph file, or the nodes would sit on another line.
    if (!io_.map.connected()) throw BadInput("input 'map' must be wired: the racing line is kept inside its edges");
  }

  void step(Context& ctx) override {
    for (auto& e : io_.estimate.take()) {
      const auto& c = e->covariance();  // row-major over (x, y, yaw)
      poses_.add(e->header().stamp_ns(), {e->x(), e->y(), e->yaw()}, pose_spread(c[0], c[4], c[8]));
      car_ = e;
    }
    if (!run_->started()) {  // the racing line, the graph and the planner, once the map is known
      const auto w = plugins::newest(io_.map);  // wired: configure says so
      if (!w) return;
      try {
        ctx.log(LogLevel::info, run_->start(plugins::from_message(*w)));
      } catch (const RoadGraphInputError& e) {
        throw BadInput(e.what());
      }
    }
    if (poses_.empty()) return;
    if (auto t = io_.tracks.take(); !t.empty()) run_->set_cars(moving_cars(*t.back()));
    // Obstacles into the map frame with the estimate at their stamp.
    std::vector<MapObstacle> seen;
    for (auto& list : io_.obstacles.take()) run_->place(*pose_at(poses_, list->header().stamp_ns()), detections(*list), seen);
    run_->observe(seen, ctx.now_ns());
    const std::optional<CyclePlan> plan = run_->plan(car_->x(), car_->y(), car_->speed());
    if (!plan) return;
    if (!plan->warning.empty()) ctx.log(LogLevel::warn, plan->warning);
    publish(ctx, *plan);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : run_->metrics(seq_)) ctx.metric(name, value);
    const LatticeDrawing lattice = run_->lattice_near_obstacles();
    if (!lattice.x.empty()) {
      ctx.metric("lattice_near_obstacles_x", lattice.x);
      ctx.metric("lattice_near_obstacles_y", lattice.y);
    }
  }

 private:
  void publish(Context& ctx, const CyclePlan& plan) {
    auto m = std::make_shared<msgs::Path>();
    m->header().frame_id("map");
    m->header().stamp_ns(ctx.now_ns());
    m->header().seq(seq_++);
    const PathGeometry& g = plan.path;
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      msgs::Pose2D pose;
      pose.x(g.x[i]);
      pose.y(g.y[i]);
      pose.yaw(g.yaw[i]);
      m->poses().push_back(pose);
    }
    m->curvature(g.curvature);
    m->s(g.s);
    m->speed(plan.speed);
    io_.path.publish(std::shared_ptr<const msgs::Path>(m));
  }

  std::optional<RoadGraphRun> run_;
  PoseHistory poses_{256};
  std::shared_ptr<const msgs::LocalizationEstimate> car_;  // the newest estimate
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(RoadGraphNode)
