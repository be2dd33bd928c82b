// Issue 7's benchmark (docs/planning.md): on IMS with the pylons of configs/ims_obstacles.json —
//  - the replanning cycle of planning.road_graph (RoadGraphPlanner::plan: the car's place,
//    obstacles to the line's frame, commitment, the search over 300 m, the path and its speeds),
//    along a drive past the pylons at 31 m/s and 20 Hz, the car put on each plan 1/20 s later;
//  - the search alone beside the Python reference (bench/baselines/road_graph_search.py), the same
//    dynamic programme on the same graph file and queries, run in the same process tree; the two
//    must choose the same nodes;
//  - the same cycle with 3 opponents (issue 46): moving cars ahead on the line at 90 % of our pace,
//    one in the path's way and two aside, their detections left out of the obstacles
//    (not_moving_cars) and the path's speeds capped to follow (follow_speed), beside the cycle
//    without them in the same run;
//  - graph build, save and load times, and the minimum-curvature QP for IMS.
// One thread; medians. Exits 1 unless the Python reference answered every query with the nodes
// ours chose (its figures compare nothing otherwise).
// usage: bench_planning [--quick] [OUT_DIR]   (--quick: one build, load and QP; queries every 25 m)
#include "planning/common/follow.hpp"
#include "planning/common/graph_search.hpp"
#include "planning/common/line_setup.hpp"
#include "sim/common/track.hpp"
#include "planning/common/min_curvature.hpp"
#include "planning/common/road_graph_planner.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

using namespace brickyard;
using namespace brickyard::planning;
using Clock = std::chrono::steady_clock;

namespace {
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}
double pct(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()))];
}
}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string out_dir = "/tmp";
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--quick") quick = true;
    else out_dir = argv[i];
  const int repeats = quick ? 1 : 5, searches = quick ? 3 : 7;
  const double query_step_m = quick ? 25 : 10;
  const std::string src = BRICKYARD_SOURCE_DIR;
  sim::WorldSpec w;
  w.line = sim::load_centerline_csv(src + "/data/tracks/IMS.csv");
  // The pylons of configs/ims_obstacles.json.
  for (auto [s, d] : {std::pair{40.0, 1.0}, {40.0, 5.0}, {190.0, -1.0}, {190.0, -5.0}}) {
    sim::Pylon p;
    p.s = s;
    p.d = d;
    w.pylons.push_back(p);
  }
  const sim::Track track(w);
  const sim::CenterLine raw = sim::load_xy_csv(src + "/data/racelines/IMS.csv");
  const motion::VehicleLimits d;
  const motion::VehicleLimits lim = motion::independent_limits(31, d.a_lat, d.a_accel, d.a_decel);
  const double edge_margin = 3.5;
  const Reference ref = make_reference(raw, &track, edge_margin, lim);
  const RoadGraphParams gp;

  std::vector<double> build_ms, load_ms, qp_ms;
  RoadGraph graph;
  for (int i = 0; i < (quick ? 1 : 3); ++i) {
    const auto t0 = Clock::now();
    graph = RoadGraph::build(ref.line, track_room(track, ref.line), gp, reference_digest(raw, edge_margin, gp));
    build_ms.push_back(ms_since(t0));
  }
  const std::string file = out_dir + "/bench_planning_ims.byrg";
  graph.save(file);
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    const RoadGraph g = RoadGraph::load(file);
    load_ms.push_back(ms_since(t0));
  }
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    const auto r = min_curvature_line({w.line.x, w.line.y, w.line.width_left, w.line.width_right}, MinCurvatureParams{});
    qp_ms.push_back(ms_since(t0));
  }

  // The drive: from 300 m before the line to 250 m past it, 20 plans a second at 31 m/s.
  PlannerParams pp;
  pp.limits.v_max = lim.v_max;
  pp.limits.ellipse = false;
  RoadGraphPlanner planner(graph, ref.line, ref.speed, pp);
  std::vector<MapObstacle> pylons;
  for (const auto& p : track.spec().pylons) pylons.push_back({p.x, p.y, p.radius, 0});
  const double v = 31, dt = 0.05;
  const Eigen::Vector2d on_centre = track.position(track.at(3720, 0));
  Eigen::Vector2d car = ref.line.point(ref.line.to_frenet(on_centre.x(), on_centre.y()).x());  // on the racing line
  std::vector<double> cycle_ms;
  std::vector<std::uint32_t> starts;
  double min_gap = 1e9;
  int cycles = 0, no_route = 0;
  for (double t = 0; t < 550 / v; t += dt, ++cycles) {
    const auto now = static_cast<std::int64_t>(t * 1e9);
    const auto t0 = Clock::now();
    planner.observe(pylons, now);
    const PlannedPath& path = planner.plan(car.x(), car.y(), v);
    cycle_ms.push_back(ms_since(t0));
    no_route += !path.route_found;
    // Next pose: v * dt along the path from the car's place on it.
    std::size_t i = 0;
    double best = 1e18;
    for (std::size_t k = 0; k < path.points.size(); ++k) {
      const double d = std::hypot(path.points[k].x - car.x(), path.points[k].y - car.y());
      if (d < best) { best = d; i = k; }
    }
    double go = v * dt;
    while (i + 1 < path.points.size()) {
      const double seg = std::hypot(path.points[i + 1].x - path.points[i].x, path.points[i + 1].y - path.points[i].y);
      if (seg >= go) {
        const double u = go / seg;
        car = {path.points[i].x + u * (path.points[i + 1].x - path.points[i].x), path.points[i].y + u * (path.points[i + 1].y - path.points[i].y)};
        break;
      }
      go -= seg;
      ++i;
    }
    for (const auto& p : track.spec().pylons) min_gap = std::min(min_gap, std::hypot(p.x - car.x(), p.y - car.y()) - p.radius - gp.half_width);
  }

  // The drive again with 3 opponents: a detection list each cycle (the pylons and the cars, the
  // car's vehicle frame), the cars' detections left out, the pylons planned round, the speeds
  // capped to follow the first car in the way.
  std::vector<double> rival_ms, static_ms;
  int following = 0;
  {
    RoadGraphPlanner with_cars(graph, ref.line, ref.speed, pp);
    const FollowParams fp;
    const double s0 = ref.line.to_frenet(car.x(), car.y()).x();
    Eigen::Vector2d ego = ref.line.point(ref.line.wrap(s0 - 550));
    const std::pair<double, double> start[3] = {{60, 0}, {120, 4}, {30, -4}};  // m ahead, m across
    for (double t = 0; t < 550 / v; t += dt) {
      const auto now = static_cast<std::int64_t>(t * 1e9);
      const double s_ego = ref.line.to_frenet(ego.x(), ego.y()).x(), yaw = ref.line.heading(s_ego);
      const StampedPose at{now, ego.x(), ego.y(), yaw, 0.05, 0.002};
      const double c = std::cos(yaw), sn = std::sin(yaw);
      auto local = [&](double x, double y) { return std::pair{c * (x - ego.x()) + sn * (y - ego.y()), -sn * (x - ego.x()) + c * (y - ego.y())}; };
      std::vector<Detection> list;
      for (const auto& p : track.spec().pylons) {
        const auto [lx, ly] = local(p.x, p.y);
        list.push_back({lx, ly, 2 * p.radius, 2 * p.radius});
      }
      std::vector<MovingCar> cars;
      for (const auto& [ahead, across] : start) {
        const double sc = ref.line.wrap(s_ego + ahead - 0.1 * v * t);  // 90 % of our pace: closing at 0.1 v
        const Eigen::Vector2d xy = ref.line.point(sc, across);
        const double h = ref.line.heading(sc);
        cars.push_back({xy.x(), xy.y(), 0.9 * v * std::cos(h), 0.9 * v * std::sin(h), 0.3, 4.9, 1.94});
        const auto [lx, ly] = local(xy.x(), xy.y());
        list.push_back({lx, ly, 4.9, 1.94});
      }
      for (bool moving : {false, true}) {
        RoadGraphPlanner& pl = moving ? with_cars : planner;
        const auto t0 = Clock::now();
        const std::vector<Detection> standing = moving ? not_moving_cars(at, list, cars, fp) : list;
        std::vector<MapObstacle> seen;
        place_detections(at, standing, nullptr, 1.0, 2.0, seen);
        pl.observe(seen, now);
        const PlannedPath& path = pl.plan(ego.x(), ego.y(), v);
        if (moving) following += std::isfinite(follow_speed(path.points, ego.x(), ego.y(), v, pp.search.car_front, gp.half_width, cars, fp));
        (moving ? rival_ms : static_ms).push_back(ms_since(t0));
      }
      ego = ref.line.point(ref.line.wrap(s_ego + v * dt));
    }
  }

  // The search alone, ours and Python's, on queries from along the drive: start nodes every
  // 10 m from 200 m before the first pylons to the second set.
  GraphSearch search(graph);
  std::vector<FrenetObstacle> obs;
  for (const auto& p : track.spec().pylons) {
    const Eigen::Vector2d f = ref.line.to_frenet(p.x, p.y);
    obs.push_back({f.x(), f.y(), p.radius});
  }
  const SearchParams sp = pp.search;
  nlohmann::json queries = nlohmann::json::array();
  std::vector<std::vector<std::uint32_t>> ours;
  std::vector<double> ours_ms;
  const double s_first = ref.line.to_frenet(track.spec().pylons[0].x, track.spec().pylons[0].y).x();
  for (double back = 200; back >= -150; back -= query_step_m) {
    const std::uint32_t start = graph.nearest_node(graph.layer_at_or_after(s_first - back), 0.0);
    std::vector<double> runs;
    Plan plan;
    for (int r = 0; r < searches; ++r) {
      const auto t0 = Clock::now();
      plan = search.plan(start, obs, sp);
      runs.push_back(ms_since(t0));
    }
    ours_ms.push_back(median(runs));
    ours.push_back(plan.nodes);
    nlohmann::json o = nlohmann::json::array();
    for (const auto& x : obs) o.push_back({{"s", x.s}, {"d", x.d}, {"radius", x.radius}});
    queries.push_back({{"start", start}, {"obstacles", o},
                       {"params", {{"horizon", sp.horizon}, {"clearance", sp.clearance}, {"soft_clearance", sp.soft_clearance},
                                   {"car_front", sp.car_front}, {"car_rear", sp.car_rear}, {"k_length", sp.k_length},
                                   {"k_curvature", sp.k_curvature}, {"k_deviation", sp.k_deviation}, {"k_proximity", sp.k_proximity}}}});
  }
  const std::string qfile = out_dir + "/bench_planning_queries.json";
  std::ofstream(qfile) << queries.dump();
  const std::string cmd = "python3 " + src + "/bench/baselines/road_graph_search.py " + file + " " + qfile;
  std::vector<double> py_ms;
  int same = 0, k = 0;
  int py_status = -1;
  if (FILE* py = popen(cmd.c_str(), "r")) {
    char line[1 << 16];
    while (std::fgets(line, sizeof line, py)) {
      const auto j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_discarded() || !j.contains("ms") || !j.contains("nodes")) break;
      py_ms.push_back(j["ms"].get<double>());
      if (k < static_cast<int>(ours.size()) && j["nodes"].get<std::vector<std::uint32_t>>() == ours[k]) ++same;
      ++k;
    }
    py_status = pclose(py);
  }
  if (py_status != 0 || k != static_cast<int>(ours.size())) {
    std::fprintf(stderr, "bench_planning: the Python reference answered %d of %zu queries (exit status %d): %s\n", k, ours.size(),
                 py_status, cmd.c_str());
    return 1;
  }

  std::printf("IMS road graph: %zu layers, %zu nodes, %zu edges (%.1f MB file)\n\n", graph.layers().size(), graph.node_count(),
              graph.edge_count(), static_cast<double>(std::ifstream(file, std::ios::binary | std::ios::ate).tellg()) / 1e6);
  std::printf("| measure | ours | baseline (same run) |\n|---|---|---|\n");
  std::printf("| replanning cycle, median / p95 (%d cycles, 31 m/s past the pylons) | %.3f / %.3f ms | — |\n", cycles,
              median(cycle_ms), pct(cycle_ms, 0.95));
  std::printf("| replanning cycle with 3 opponents, median / p95 (%zu cycles: detections, 2 of 3 cars aside, following %d) | %.3f / %.3f ms | %.3f / %.3f ms (the same cycles, the cars as obstacles) |\n",
              rival_ms.size(), following, median(rival_ms), pct(rival_ms, 0.95), median(static_ms), pct(static_ms, 0.95));
  std::printf("| graph search, median of %zu queries | %.3f ms | %.1f ms (Python reference, same graph and queries) |\n",
              ours_ms.size(), median(ours_ms), median(py_ms));
  std::printf("| search speed-up | **%.0fx** | same nodes chosen: %d of %zu |\n", median(py_ms) / median(ours_ms), same, ours.size());
  std::printf("| graph build (median of %zu) | %.0f ms | — |\n", build_ms.size(), median(build_ms));
  std::printf("| graph file load (median of %d) | %.1f ms | — |\n", repeats, median(load_ms));
  std::printf("| minimum-curvature QP, IMS, margin 1.5 m (median of %d) | %.0f ms | — |\n", repeats, median(qp_ms));
  std::printf("\ndrive: %d plans without a route; least gap between the car's side and a pylon on the plans: %.2f m\n",
              no_route, min_gap);
  if (same != k) std::fprintf(stderr, "bench_planning: the Python reference chose other nodes on %d of %d queries\n", k - same, k);
  return same == k ? 0 : 1;
}
