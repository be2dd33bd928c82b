// planning.road_graph: the paper's obstacle-avoiding planner. A lattice along the racing line
// (built from the map at start, or loaded from a file `brickyard-plan graph` wrote) is searched
// at rate_hz from the car's estimate around the obstacles perception reports; the Path it
// publishes runs horizon metres ahead with speeds. Same ports and line parameters as
// planning.racing_line, so the two swap by the plugin's name. Algorithms:
// ../common/road_graph_planner.hpp; the frames and the Path's geometry: ../common/plan_frames.hpp.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/plugin.hpp>

#include "../common/line_setup.hpp"
#include "../line_params.hpp"
#include "../common/plan_frames.hpp"
#include "../common/road_graph_planner.hpp"
#include "map_msg.hpp"
#include "newest.hpp"
#include "vehicle_param.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <set>
#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::planning;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  // The car's size: the vehicle file's unless the graph overrides it (NaN: off).
  std::optional<double> half_width, car_front, car_rear;
  LineSettings line;
  double rate_hz = 20;
  double obstacle_edge_band = 1.0;
  double obstacle_place_sigmas = 2.0;
  bool car_curvature = false;   // curvature_limit car: the graph's edges and the search from the car's steering and speed
  double steer_margin = 0.8;
  std::string graph_file;
  RoadGraphParams graph;
  PlannerParams planner;
};

ParamBinding<Settings> bindings() {
  using G = RoadGraphParams;
  using S = SearchParams;
  using P = PlannerParams;
  constexpr auto graph = &Settings::graph;
  constexpr auto planner = &Settings::planner;
  constexpr auto search = &P::search;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its width and length around base_link");
  bind_line(b, &Settings::line);
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(0.1, 1000).doc("replanning rate");
  b.bind("graph_file", &Settings::graph_file).doc("a graph written by `brickyard-plan graph`; empty: built from the map at start");
  b.bind("layer_spacing", graph, &G::layer_spacing).in_unit("m").range(1, 100);
  b.bind("layer_spacing_turn", graph, &G::layer_spacing_turn).in_unit("m").range(1, 100);
  b.bind("lateral_step", graph, &G::lateral_step).in_unit("m").range(0.1, 5);
  b.bind("half_width", &Settings::half_width).in_unit("m").range(0.1, 5).doc("half the car's width; default: the vehicle file's");
  b.bind("graph_edge_margin", graph, &G::edge_margin).in_unit("m").range(0, 100)
      .doc("nodes keep this much beyond half the width from the track edges");
  b.bind("max_curvature", graph, &G::max_curvature).in_unit("1/m").range(0.001, 1).doc("sharper edges are dropped (curvature_limit constant)");
  b.bind_choice("curvature_limit", {{"constant", false}, {"car", true}}, &Settings::car_curvature)
      .doc("constant: max_curvature; car: edges no sharper than steer_margin of the vehicle file's steering turns, and a lane change "
           "only where the car, braking from its speed, can be slow enough for it at the file's lateral acceleration");
  b.bind("steer_margin", &Settings::steer_margin).range(0.1, 1).doc("curvature_limit car: the share of the steering limit an edge may ask");
  b.bind("max_edge_length", graph, &G::max_edge_length).in_unit("m").range(5, 500);
  b.bind("horizon", planner, search, &S::horizon).in_unit("m").range(20, 2000);
  b.bind("clearance", planner, search, &S::clearance).in_unit("m").range(0, 100).doc("least gap between the car's side and an obstacle");
  b.bind("swerve_edge_margin", planner, &P::swerve_edge_margin).in_unit("m").range(0, 100)
      .doc("with no route round an obstacle in the graph, an emergency swerve past it may keep the car's side this near the track's edge");
  b.bind("keep_clearance", planner, &P::keep_clearance).in_unit("m").range(0, 100)
      .doc("a plan already made is dropped only when an obstacle comes nearer than this (detections move by centimetres); "
           "with no way at clearance, the search tries this before the car stops (at most clearance)");
  b.bind("soft_clearance", planner, search, &S::soft_clearance).in_unit("m").range(0, 100);
  b.bind("car_front", &Settings::car_front).in_unit("m").range(0, 20).doc("car ahead of base_link; default: the vehicle file's");
  b.bind("car_rear", &Settings::car_rear).in_unit("m").range(0, 20).doc("car behind base_link; default: the vehicle file's");
  b.bind("k_length", planner, search, &S::k_length).range(0, 1e6);
  b.bind("k_curvature", planner, search, &S::k_curvature).range(0, 1e8);
  b.bind("k_deviation", planner, search, &S::k_deviation).range(0, 1e6);
  b.bind("k_proximity", planner, search, &S::k_proximity).range(0, 1e6);
  b.bind("commit_time", planner, &P::commit_time).in_unit("s").range(0, 10);
  b.bind("commit_min", planner, &P::commit_min).in_unit("m").range(1, 1000);
  b.bind("rejoin_reach", planner, &P::rejoin_reach).in_unit("m").range(0, 1000)
      .doc("with no route from the layer at the commitment distance, lead-ins this much farther are tried (a stopped car rejoins the band)");
  b.bind("obstacle_memory", planner, &P::obstacle_memory).in_unit("s").range(0, 3600);
  b.bind("obstacle_fusion", planner, &P::obstacle_fusion)
      .doc("a remembered obstacle's place fuses its detections by their spread (off: each detection replaces it)");
  b.bind("obstacle_drift", planner, &P::obstacle_drift).in_unit("m/s").range(0, 100)
      .doc("how fast a remembered obstacle may move: its place fuses the detections by their spread, and its own spread grows by this a second");
  b.bind("obstacle_edge_band", &Settings::obstacle_edge_band).in_unit("m").range(0, 10)
      .doc("a detection whose centre is less than this inside a track edge (or beyond it) is the wall or beside the track: not planned around");
  b.bind("obstacle_place_sigmas", &Settings::obstacle_place_sigmas).range(0, 10)
      .doc("the edge band grows by this many standard deviations of the detection's place in the map (the estimate's position, "
           "and its heading times the range)");
  b.bind("obstacle_confirmations", planner, &P::confirmations).range(1, 100)
      .doc("frames an obstacle must be detected in before it is planned around");
  return b;
}

struct Ports {
  Input<msgs::TrackMap> map;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::ObstacleList> obstacles;
  Output<msgs::Path> path;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("map", &Ports::map).doc("the track: the graph's room and the line's edge margin (must be wired)").optional().depth(1);
  b.input("estimate", &Ports::estimate).doc("where the car is (base_link, map frame)").optional().depth(64);
  b.input("obstacles", &Ports::obstacles).doc("obstacles in the vehicle frame, placed with the estimate of their stamp").optional();
  b.output("path", &Ports::path).doc("horizon m of path from just behind the car, with speeds (open)");
  return b;
}

class RoadGraphNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("planning.road_graph", "1.0.0")
        .describe("obstacle avoidance on a road graph (Frenet lattice) along the racing line; a Path with speeds, replanned at rate_hz")
        .with_ports(ports())
        .plays(roles::planner)
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings set = bindings().read(ctx.params());
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, set.vehicle);
    src_ = load_line(ctx, set.line, car);
    line_file_ = src_.plan ? std::string("the racing line planned for the map") : src_.file_line.source;
    gp_ = set.graph;
    pp_ = set.planner;
    edge_band_ = set.obstacle_edge_band;
    place_sigmas_ = set.obstacle_place_sigmas;
    gp_.half_width = set.half_width.value_or(car.half_width);
    pp_.search.car_front = set.car_front.value_or(car.front);
    pp_.search.car_rear = set.car_rear.value_or(car.rear);
    pp_.limits = src_.limits;  // as the racing line's profile: the two planners agree on a clear track
    if (set.car_curvature) {  // the car's tightest turn, and the lateral grip its speed leaves (graph_search.hpp)
      gp_.max_curvature = std::clamp(std::tan(set.steer_margin * car.max_steer) / car.wheelbase, 0.001, 1.0);
      pp_.search.lateral_accel = car.a_lat;
      pp_.search.brake = car.a_decel;
    }
    const std::string& gf = set.graph_file;
    if (!gf.empty()) {
      if (src_.plan)
        throw BadInput("graph_file needs a raceline file: with raceline plan the line (and so the graph) is made from the map at start");
      graph_file_ = ctx.find_file(gf);
      try {
        loaded_ = std::make_unique<RoadGraph>(RoadGraph::load(graph_file_));
      } catch (const std::exception& e) {
        throw BadInput(std::string("graph_file ") + e.what());
      }
      if (!(loaded_->params() == gp_))
        throw BadInput("graph_file " + graph_file_ + " was built with other graph parameters than this node's (rebuild it with brickyard-plan graph and the same options)");
      if (loaded_->source_digest() != reference_digest(src_.file_line, src_.edge_margin, gp_))
        throw BadInput("graph_file " + graph_file_ + " was built for another racing line, edge_margin or graph parameters (rebuild it with brickyard-plan graph)");
    }
    io_ = ports().connect(ctx);
    // The line is kept inside the track's edges as the graph was built: the map is needed even
    // with a graph file, or the nodes would sit on another line.
    if (!io_.map.connected()) throw BadInput("input 'map' must be wired: the racing line is kept inside its edges");
  }

  void step(Context& ctx) override {
    for (auto& e : io_.estimate.take()) {
      poses_.push_back(e);
      if (poses_.size() > 256) poses_.pop_front();
    }
    if (!planner_ && !setup(ctx)) return;
    if (poses_.empty()) return;
    // Obstacles into the map frame with the estimate at their stamp.
    std::vector<MapObstacle> seen;
    std::vector<StampedPose> poses;
    for (auto& list : io_.obstacles.take()) {
      if (poses.empty())
        for (const auto& e : poses_) {
          const auto& cov = e->covariance();  // row-major over (x, y, yaw)
          poses.push_back({e->header().stamp_ns(), e->x(), e->y(), e->yaw(), std::sqrt(std::max({cov[0], cov[4], 0.0})),
                           std::sqrt(std::max(cov[8], 0.0))});
        }
      const StampedPose at = pose_at(poses, list->header().stamp_ns());
      for (const auto& o : list->obstacles())
        if (auto m = obstacle_in_map(at, o.x(), o.y(), o.size_x(), o.size_y())) {
          if (track_ && !on_track(*track_, m->x, m->y, placement_band(at, o.x(), o.y(), edge_band_, place_sigmas_))) ++off_track_;
          else seen.push_back(*m);
        }
    }
    planner_->observe(seen, ctx.now_ns());
    // The layers around the obstacles met, for the report's drawing of the lattice.
    for (const auto& o : planner_->obstacles()) {
      const Eigen::Vector2d f = line_ready_.line.to_frenet(o.x, o.y);
      if (!std::isfinite(f.x())) continue;
      for (double s = f.x() - 150; s <= f.x() + 100; s += 1.0) shown_layers_.insert(graph_->layer_at_or_after(s));
    }
    const msgs::LocalizationEstimate& car = *poses_.back();
    if (!(std::abs(car.x()) < 1e7 && std::abs(car.y()) < 1e7)) return;  // NaN or absurd: no plan from it
    const PlannedPath& plan = planner_->plan(car.x(), car.y(), car.speed());
    if (plan.points.size() < 2) return;
    if (!plan.route_found) {
      // Once per episode: which obstacles closed the road (the car brakes for them).
      if (!stopping_) {
        std::string what;
        for (const auto& o : planner_->obstacles()) {
          const Eigen::Vector2d f = line_ready_.line.to_frenet(o.x, o.y);
          char b[96];
          std::snprintf(b, sizeof b, "%s(s %.1f, d %.1f, r %.2f)", what.empty() ? "" : ", ", f.x(), f.y(), o.radius);
          what += b;
        }
        const Eigen::Vector2d c = line_ready_.line.to_frenet(car.x(), car.y());
        char b[160];
        std::snprintf(b, sizeof b, "no route: %s (car at s %.1f, d %.1f); obstacles: ",
                      plan.swerve_short ? "no room to stop: swerving as far as the car can, braking"
                      : plan.swerve     ? "an emergency swerve past, braking"
                                        : "braking to a stop", c.x(), c.y());
        ctx.log(LogLevel::warn, b + (what.empty() ? std::string("none") : what));
      }
      stopping_ = true;
      ++blocked_;
    } else {
      stopping_ = false;
    }
    if (plan.restarted) ++restarts_;
    if (plan.swerve) ++swerves_;
    obstacles_max_ = std::max(obstacles_max_, planner_->obstacles().size());
    std::size_t confirmed = 0;  // seen often enough to be planned around
    for (const auto& o : planner_->obstacles()) confirmed += o.seen >= pp_.confirmations;
    planned_around_max_ = std::max(planned_around_max_, confirmed);
    auto m = std::make_shared<msgs::Path>();
    m->header().frame_id("map");
    m->header().stamp_ns(ctx.now_ns());
    m->header().seq(seq_++);
    const PathGeometry g = path_geometry(plan.points);
    for (std::size_t i = 0; i < g.x.size(); ++i) {
      msgs::Pose2D pose;
      pose.x(g.x[i]);
      pose.y(g.y[i]);
      pose.yaw(g.yaw[i]);
      m->poses().push_back(pose);
    }
    m->curvature(g.curvature);
    m->s(g.s);
    max_offset_ = std::max(max_offset_, g.max_offset);
    m->speed(plan.speed);
    io_.path.publish(std::shared_ptr<const msgs::Path>(m));
  }

  void deactivate(Context& ctx) override {
    ctx.metric("plans", static_cast<double>(seq_));
    ctx.metric("plans_without_route", static_cast<double>(blocked_));
    ctx.metric("restarts", static_cast<double>(restarts_));
    ctx.metric("obstacles_remembered_max", static_cast<double>(obstacles_max_));
    ctx.metric("obstacles_planned_around_max", static_cast<double>(planned_around_max_));
    ctx.metric("emergency_swerves", static_cast<double>(swerves_));
    ctx.metric("detections_off_track", static_cast<double>(off_track_));
    if (planner_) {
      ctx.metric("planned_lap_s", planned_lap_s_);
      ctx.metric("line_length_m", line_ready_.racing.length);
    }
    ctx.metric("max_offset_from_line_m", max_offset_);
    if (graph_) {
      ctx.metric("graph_nodes", static_cast<double>(graph_->node_count()));
      ctx.metric("graph_edges", static_cast<double>(graph_->edge_count()));
      // The lattice's nodes (map frame) from 150 m before to 100 m past every obstacle met.
      std::vector<double> xs, ys;
      for (int l : shown_layers_) {
        const auto& L = graph_->layers()[l];
        for (std::uint32_t n = L.first_node; n < L.first_node + L.count; ++n) {
          const Eigen::Vector2d q = line_ready_.line.point(L.s, graph_->node_d(n));
          xs.push_back(q.x());
          ys.push_back(q.y());
        }
      }
      if (!xs.empty()) {
        ctx.metric("lattice_near_obstacles_x", xs);
        ctx.metric("lattice_near_obstacles_y", ys);
      }
    }
  }

 private:
  // The racing line, the graph and the planner, once the map is known.
  bool setup(Context& ctx) {
    std::shared_ptr<const msgs::TrackMap> w;
    if (io_.map.connected()) {
      w = plugins::newest(io_.map);
      if (!w) return false;
    }
    try {
      std::unique_ptr<track::Track>& track = track_;
      if (w) track = std::make_unique<track::Track>(plugins::from_message(*w));
      line_ready_ = make_reference(src_, track.get());
      if (loaded_) {
        graph_ = std::move(loaded_);
      } else {
        if (!track) throw BadInput("no map to build the road graph from");
        graph_ = std::make_unique<RoadGraph>(RoadGraph::build(line_ready_.line, track_room(*track, line_ready_.line), gp_, reference_digest(src_.file_line, src_.edge_margin, gp_)));
      }
      planner_ = std::make_unique<RoadGraphPlanner>(*graph_, line_ready_.line, line_ready_.speed, pp_);
      planned_lap_s_ = planned_lap(line_ready_.racing);
    } catch (const BadInput&) {
      throw;
    } catch (const std::exception& e) {
      throw BadInput(std::string("road graph for ") + line_file_ + ": " + e.what());
    }
    ctx.log(LogLevel::info, "road graph " + (graph_file_.empty() ? std::string("built from the map") : "loaded from " + graph_file_) +
                                ": " + std::to_string(graph_->layers().size()) + " layers, " + std::to_string(graph_->node_count()) +
                                " nodes, " + std::to_string(graph_->edge_count()) + " edges");
    return true;
  }

  LineSource src_;
  std::string line_file_, graph_file_;
  RoadGraphParams gp_;
  PlannerParams pp_;
  Reference line_ready_;
  std::unique_ptr<RoadGraph> loaded_, graph_;
  std::unique_ptr<RoadGraphPlanner> planner_;
  std::deque<std::shared_ptr<const msgs::LocalizationEstimate>> poses_;
  std::uint32_t seq_ = 0;
  std::size_t blocked_ = 0, restarts_ = 0, swerves_ = 0, obstacles_max_ = 0, planned_around_max_ = 0, off_track_ = 0;
  double edge_band_ = 1.0, place_sigmas_ = 2.0, planned_lap_s_ = 0;
  std::unique_ptr<track::Track> track_;  // the map's, once it came
  bool stopping_ = false;
  double max_offset_ = 0;
  std::set<int> shown_layers_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(RoadGraphNode)
