#pragma once
// planning.road_graph's parameters (plugin.cpp): the car's file, the racing line's (shared with
// planning.racing_line), the rate, a graph file, and the car's size, the obstacles', the graph's
// and the planner's (common/road_graph_run.hpp). Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "planning/common/road_graph_run.hpp"
#include "planning/line_params.hpp"
#include "vehicle_param.hpp"

#include <string>

namespace brickyard::planning {

// What the graph says: the road graph's own settings (bound as members of this struct), and the
// car's file, the line, the rate and the graph file the plugin reads itself.
struct Settings : RoadGraphSettings {
  std::string vehicle = plugins::default_vehicle_file;
  LineSettings line;
  double rate_hz = 20;
  double step_deadline_s = 10;
  std::string graph_file;
};

inline ParamBinding<Settings> bindings() {
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
  // Its first step with the map plans the line and builds the road graph (about half a second
  // at IMS here, more on a longer track or a loaded host): the allowance the default deadline
  // (ten periods, 0.5 s) would not give. Later steps plan in milliseconds.
  b.bind("step_deadline_s", &Settings::step_deadline_s).in_unit("s").range(0, 3600)
      .doc("the node's step deadline, wall time, the graph's build included (0: derived from its trigger, docs/reliability.md)");
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
  using F = FollowParams;
  b.bind("follow_headway_s", &Settings::follow, &F::headway_s).in_unit("s").range(0, 10)
      .doc("a moving car followed (input tracks) is kept this many seconds of its speed ahead, beyond follow_min_gap");
  b.bind("follow_min_gap", &Settings::follow, &F::min_gap).in_unit("m").range(0, 1000).doc("least gap between the bumpers at any speed");
  b.bind("follow_decel", &Settings::follow, &F::decel).in_unit("m/s^2").range(0.5, 50)
      .doc("the braking the follow cap allows to close a gap");
  return b;
}

// What configure reads from the files the settings name — the car, the racing line, a graph file
// — read the same way at validation (Manifest::check). `files`: the Context or the CheckView.
struct RoadGraphInputs {
  LineSource line;
  RoadGraphConfig config;
  std::string graph_file;  // where it was found; empty: none (built from the map at start)
  std::unique_ptr<RoadGraph> graph;
};

template <class Files> RoadGraphInputs read_inputs(const Files& files, const Settings& set) {
  const vehicle::Vehicle car = plugins::read_vehicle_file(files.find_file(set.vehicle));
  RoadGraphInputs in;
  in.line = load_line(files, set.line, car);
  in.config = road_graph_config(set, car, in.line.limits);
  if (set.graph_file.empty()) return in;
  if (in.line.plan)
    throw BadInput("graph_file needs a raceline file: with raceline plan the line (and so the graph) is made from the map at start");
  in.graph_file = files.find_file(set.graph_file);
  try {
    in.graph = load_graph_file(in.graph_file, in.line, in.config.graph);
  } catch (const RoadGraphInputError& e) {
    throw BadInput(e.what());
  }
  return in;
}

}  // namespace brickyard::planning
