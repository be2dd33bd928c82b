#include "road_graph_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace brickyard::planning {

RoadGraphConfig road_graph_config(const RoadGraphSettings& s, const vehicle::Vehicle& car, const VehicleLimits& limits) {
  RoadGraphConfig c;
  c.graph = s.graph;
  c.planner = s.planner;
  c.follow = s.follow;
  c.edge_band = s.obstacle_edge_band;
  c.place_sigmas = s.obstacle_place_sigmas;
  c.graph.half_width = s.half_width.value_or(car.half_width);
  c.planner.search.car_front = s.car_front.value_or(car.front);
  c.planner.search.car_rear = s.car_rear.value_or(car.rear);
  c.planner.limits = limits;
  if (s.car_curvature) {
    c.graph.max_curvature = std::clamp(std::tan(s.steer_margin * car.max_steer) / car.wheelbase, 0.001, 1.0);
    c.planner.search.lateral_accel = car.a_lat;
    c.planner.search.brake = car.a_decel;
  }
  return c;
}

std::unique_ptr<RoadGraph> load_graph_file(const std::string& path, const LineSource& src, const RoadGraphParams& graph) {
  std::unique_ptr<RoadGraph> loaded;
  try {
    loaded = std::make_unique<RoadGraph>(RoadGraph::load(path));
  } catch (const std::exception& e) {
    throw RoadGraphInputError(std::string("graph_file ") + e.what());
  }
  if (!(loaded->params() == graph))
    throw RoadGraphInputError("graph_file " + path +
                              " was built with other graph parameters than this node's (rebuild it with brickyard-plan graph and the "
                              "same options)");
  if (loaded->source_digest() != reference_digest(src.file_line, src.edge_margin, graph))
    throw RoadGraphInputError("graph_file " + path +
                              " was built for another racing line, edge_margin or graph parameters (rebuild it with brickyard-plan graph)");
  return loaded;
}

RoadGraphRun::RoadGraphRun(LineSource src, RoadGraphConfig config, std::unique_ptr<RoadGraph> loaded, std::string graph_file)
    : src_(std::move(src)), config_(std::move(config)), graph_file_(std::move(graph_file)), loaded_(std::move(loaded)) {
  line_file_ = src_.plan ? std::string("the racing line planned for the map") : src_.file_line.source;
}

std::string RoadGraphRun::start(track::TrackGeometry map) {
  try {
    track_ = std::make_unique<track::Track>(std::move(map));
    line_ready_ = make_reference(src_, track_.get());
    if (loaded_) {
      graph_ = std::move(loaded_);
    } else {
      graph_ = std::make_unique<RoadGraph>(RoadGraph::build(line_ready_.line, track_room(*track_, line_ready_.line), config_.graph,
                                                            reference_digest(src_.file_line, src_.edge_margin, config_.graph)));
    }
    planner_ = std::make_unique<RoadGraphPlanner>(*graph_, line_ready_.line, line_ready_.speed, config_.planner);
    planned_lap_s_ = planned_lap(line_ready_.racing);
  } catch (const std::exception& e) {
    throw RoadGraphInputError(std::string("road graph for ") + line_file_ + ": " + e.what());
  }
  return "road graph " + (graph_file_.empty() ? std::string("built from the map") : "loaded from " + graph_file_) + ": " +
         std::to_string(graph_->layers().size()) + " layers, " + std::to_string(graph_->node_count()) + " nodes, " +
         std::to_string(graph_->edge_count()) + " edges";
}

void RoadGraphRun::place(const StampedPose& at, const std::vector<Detection>& list, std::vector<MapObstacle>& seen) {
  const std::vector<Detection> standing = cars_.empty() ? list : not_moving_cars(at, list, cars_, config_.follow);
  car_detections_ += list.size() - standing.size();
  off_track_ += place_detections(at, standing, track_.get(), config_.edge_band, config_.place_sigmas, seen);
}

void RoadGraphRun::observe(const std::vector<MapObstacle>& seen, std::int64_t now_ns) {
  planner_->observe(seen, now_ns);
  for (const auto& o : planner_->obstacles()) {
    const Eigen::Vector2d f = line_ready_.line.to_frenet(o.x, o.y);
    if (!std::isfinite(f.x())) continue;
    for (double s = f.x() - 150; s <= f.x() + 100; s += 1.0) shown_layers_.insert(graph_->layer_at_or_after(s));
  }
}

std::optional<CyclePlan> RoadGraphRun::plan(double x, double y, double speed) {
  if (!(std::abs(x) < 1e7 && std::abs(y) < 1e7)) return std::nullopt;  // NaN or absurd: no plan from it
  const PlannedPath& plan = planner_->plan(x, y, speed);
  if (plan.points.size() < 2) return std::nullopt;
  CyclePlan out;
  if (!plan.route_found) {
    if (!stopping_) out.warning = no_route_warning(plan, x, y);
    stopping_ = true;
    ++blocked_;
  } else {
    stopping_ = false;
  }
  count(plan);
  out.path = path_geometry(plan.points);
  max_offset_ = std::max(max_offset_, out.path.max_offset);
  out.speed = plan.speed;
  follow_cars(plan, x, y, speed, out.speed);
  return out;
}

// The path's speeds no faster than following the first moving car in its way allows.
void RoadGraphRun::follow_cars(const PlannedPath& plan, double x, double y, double our_speed, std::vector<double>& speed) {
  if (cars_.empty()) return;
  double gap = 0;
  const double cap = follow_speed(plan.points, x, y, our_speed, config_.planner.search.car_front, config_.graph.half_width, cars_,
                                  config_.follow, &gap);
  min_follow_gap_ = std::min(min_follow_gap_, gap);
  if (!std::isfinite(cap)) return;
  bool capped = false;
  for (double& v : speed)
    if (v > cap) v = cap, capped = true;
  following_ += capped;
}

std::string RoadGraphRun::no_route_warning(const PlannedPath& plan, double x, double y) const {
  std::string what;
  for (const auto& o : planner_->obstacles()) {
    const Eigen::Vector2d f = line_ready_.line.to_frenet(o.x, o.y);
    char b[96];
    std::snprintf(b, sizeof b, "%s(s %.1f, d %.1f, r %.2f)", what.empty() ? "" : ", ", f.x(), f.y(), o.radius);
    what += b;
  }
  const Eigen::Vector2d c = line_ready_.line.to_frenet(x, y);
  char b[160];
  std::snprintf(b, sizeof b, "no route: %s (car at s %.1f, d %.1f); obstacles: ",
                plan.swerve_short ? "no room to stop: swerving as far as the car can, braking"
                : plan.swerve     ? "an emergency swerve past, braking"
                                  : "braking to a stop", c.x(), c.y());
  return b + (what.empty() ? std::string("none") : what);
}

void RoadGraphRun::count(const PlannedPath& plan) {
  if (plan.restarted) ++restarts_;
  if (plan.swerve) ++swerves_;
  obstacles_max_ = std::max(obstacles_max_, planner_->obstacles().size());
  std::size_t confirmed = 0;  // seen often enough to be planned around
  for (const auto& o : planner_->obstacles()) confirmed += o.seen >= config_.planner.confirmations;
  planned_around_max_ = std::max(planned_around_max_, confirmed);
}

std::vector<std::pair<std::string, double>> RoadGraphRun::metrics(std::uint32_t plans) const {
  std::vector<std::pair<std::string, double>> m = {
      {"plans", static_cast<double>(plans)},
      {"plans_without_route", static_cast<double>(blocked_)},
      {"restarts", static_cast<double>(restarts_)},
      {"obstacles_remembered_max", static_cast<double>(obstacles_max_)},
      {"obstacles_planned_around_max", static_cast<double>(planned_around_max_)},
      {"emergency_swerves", static_cast<double>(swerves_)},
      {"detections_off_track", static_cast<double>(off_track_)}};
  if (car_detections_ > 0 || following_ > 0) {
    m.emplace_back("detections_of_moving_cars", static_cast<double>(car_detections_));
    m.emplace_back("plans_following", static_cast<double>(following_));
    m.emplace_back("min_follow_gap_m", min_follow_gap_);
  }
  if (planner_) {
    m.emplace_back("planned_lap_s", planned_lap_s_);
    m.emplace_back("line_length_m", line_ready_.racing.length);
  }
  m.emplace_back("max_offset_from_line_m", max_offset_);
  if (graph_) {
    m.emplace_back("graph_nodes", static_cast<double>(graph_->node_count()));
    m.emplace_back("graph_edges", static_cast<double>(graph_->edge_count()));
  }
  return m;
}

LatticeDrawing RoadGraphRun::lattice_near_obstacles() const {
  LatticeDrawing out;
  if (!graph_) return out;
  for (int l : shown_layers_) {
    const auto& L = graph_->layers()[l];
    for (std::uint32_t n = L.first_node; n < L.first_node + L.count; ++n) {
      const Eigen::Vector2d q = line_ready_.line.point(L.s, graph_->node_d(n));
      out.x.push_back(q.x());
      out.y.push_back(q.y());
    }
  }
  return out;
}

}  // namespace brickyard::planning
