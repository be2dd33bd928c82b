// The road graph, its search, the replanning loop and the speed profile, on synthetic lines with
// known answers.
#include "planning/common/graph_search.hpp"
#include "planning/common/road_graph.hpp"
#include "planning/common/plan_frames.hpp"
#include "planning/common/road_graph_planner.hpp"
#include "planning/common/road_graph_run.hpp"
#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "vehicle/vehicle.hpp"

#include "math/fnv1a.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

using namespace brickyard::planning;

namespace {

// A counter-clockwise circle of radius r, a point every ~5 m.
RefLine circle(double r) {
  std::vector<double> x, y, k;
  const int n = static_cast<int>(2 * M_PI * r / 5);
  for (int i = 0; i < n; ++i) {
    x.push_back(r * std::cos(2 * M_PI * i / n));
    y.push_back(r * std::sin(2 * M_PI * i / n));
    k.push_back(1 / r);
  }
  return RefLine(x, y, k);
}

// A stadium: two 600 m straights joined by half circles of r (200 m), a point every ~5 m (a
// fifth of the arc's radius at most: a hairpin's points closer).
RefLine stadium(double r = 200) {
  std::vector<double> x, y, k;
  const double L = 600;
  auto arc = [&](double cx, double a0) {
    const int m = std::max(static_cast<int>(M_PI * r / 5), static_cast<int>(M_PI * 5));
    for (int i = 0; i < m; ++i) {
      const double a = a0 + M_PI * i / m;
      x.push_back(cx + r * std::cos(a));
      y.push_back(r + r * std::sin(a));
      k.push_back(1 / r);
    }
  };
  for (double s = 0; s < L; s += 5) { x.push_back(s); y.push_back(0); k.push_back(0); }
  arc(L, -M_PI / 2);
  for (double s = L; s > 0; s -= 5) { x.push_back(s); y.push_back(2 * r); k.push_back(0); }
  arc(0, M_PI / 2);
  return RefLine(x, y, k);
}

// 7 m of road to each side of the line everywhere.
const TrackRoom kRoom = [](double) { return std::make_pair(-7.0, 7.0); };

TEST(RefLine, FrenetRoundTripOnACircle) {
  const RefLine c = circle(200);
  EXPECT_NEAR(c.length(), 2 * M_PI * 200, 0.5);
  const Eigen::Vector2d p = c.point(300, -1.5);  // outside: right of a counter-clockwise circle
  EXPECT_NEAR(p.norm(), 201.5, 0.01);
  const Eigen::Vector2d f = c.to_frenet(p.x(), p.y(), 290);
  EXPECT_NEAR(f.x(), 300, 0.05);
  EXPECT_NEAR(f.y(), -1.5, 0.01);
  const Eigen::Vector2d g = c.to_frenet(p.x(), p.y());  // no hint: searches all
  EXPECT_NEAR(g.x(), 300, 0.05);
}

TEST(RoadGraph, OffsetCurvatureOfAConcentricCircle) {
  // At a constant offset d from a circle of radius R the curve is a circle of radius R - d.
  EXPECT_NEAR(offset_curvature(1 / 200.0, 3, 0, 0), 1 / 197.0, 1e-12);
  EXPECT_NEAR(offset_curvature(1 / 200.0, -3, 0, 0), 1 / 203.0, 1e-12);
  EXPECT_NEAR(offset_curvature(0, 2, 0, 0.01), 0.01, 1e-12);  // on a straight: d''
}

TEST(RoadGraph, LayersNodesAndEdgesFollowTheParameters) {
  const RefLine line = stadium();
  RoadGraphParams p;
  const RoadGraph g = RoadGraph::build(line, kRoom, p);
  // Denser layers in the turns.
  int turn = 0, straight = 0;
  for (std::size_t i = 0; i + 1 < g.layers().size(); ++i) {
    const double gap = g.layers()[i + 1].s - g.layers()[i].s;
    (std::abs(line.kappa(g.layers()[i].s)) > p.turn_curvature ? turn : straight) += 1;
    EXPECT_TRUE(std::abs(gap - p.layer_spacing) < 1e-9 || std::abs(gap - p.layer_spacing_turn) < 1e-9) << gap;
  }
  EXPECT_GT(turn, 0);
  EXPECT_GT(straight, 0);
  // Nodes: every 0.5 m within 7 - 0.97 - 1.5 of the line, the line itself one of them.
  const auto& L = g.layers()[3];
  EXPECT_EQ(L.count, 2u * 9 + 1);
  EXPECT_DOUBLE_EQ(g.node_d(L.first_node), -4.5);
  // Edges: within the curvature limit unless they follow the line; they reach forward.
  std::size_t along = 0;
  for (std::uint32_t n = 0; n < g.node_count(); ++n)
    for (auto* e = g.edges_begin(n); e != g.edges_end(n); ++e) {
      const bool same_d = g.node_d(e->to) == g.node_d(n);
      along += same_d;
      if (!same_d) {
        ASSERT_LE(e->max_kappa, p.max_curvature + 1e-6);
      }
      ASSERT_GT(e->length, 0);
      double h = g.node_s(e->to) - g.node_s(n);
      if (h <= 0) h += g.length();
      ASSERT_LE(h, p.max_edge_length + 1e-9);
    }
  EXPECT_EQ(along, g.node_count());  // exactly one "keep your lane" edge per node
}

TEST(RoadGraph, EdgeCurvatureMatchesItsPoints) {
  // The curvature the graph stores is that of the curve it stands for: three-point curvature of
  // sampled points on a lane change across a straight.
  const RefLine line = stadium();
  const EdgeShape e{100, -2, 160, 3};
  std::vector<PathSample> pts;
  sample_shape(line, e, 0.5, pts);
  double kmax = 0;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double ax = pts[i].x - pts[i - 1].x, ay = pts[i].y - pts[i - 1].y;
    const double bx = pts[i + 1].x - pts[i].x, by = pts[i + 1].y - pts[i].y;
    const double cx = pts[i + 1].x - pts[i - 1].x, cy = pts[i + 1].y - pts[i - 1].y;
    const double k = 2 * (ax * by - ay * bx) / (std::hypot(ax, ay) * std::hypot(bx, by) * std::hypot(cx, cy));
    EXPECT_NEAR(k, pts[i].kappa, 2e-4) << i;
    kmax = std::max(kmax, std::abs(k));
  }
  EXPECT_NEAR(kmax, 5.7735 * 5 / (60 * 60), 2e-4);  // smootherstep: |d''| peaks at 10/√3 Δd/h²
}

namespace {
// A crafted file's digest made to match its bytes again: what a hand-edited, not a damaged, file
// would carry, so the loader's own checks are what refuse it.
std::string resealed(std::string b) {
  const std::uint64_t sum = brickyard::math::fnv1a(std::string_view(b.data(), b.size() - 8));
  b.replace(b.size() - 8, 8, reinterpret_cast<const char*>(&sum), 8);
  return b;
}
}  // namespace

TEST(RoadGraph, SavesAndLoadsAndRejectsBrokenFiles) {
  const RoadGraph g = RoadGraph::build(stadium(), kRoom, RoadGraphParams{}, 0xABCDEF);
  const std::string path = ::testing::TempDir() + "/stadium.byrg";
  g.save(path);
  const RoadGraph h = RoadGraph::load(path);
  EXPECT_EQ(h.source_digest(), 0xABCDEFu);
  ASSERT_EQ(h.node_count(), g.node_count());
  ASSERT_EQ(h.edge_count(), g.edge_count());
  EXPECT_EQ(h.edges_begin(1234)->to, g.edges_begin(1234)->to);
  EXPECT_EQ(h.edges_begin(1234)->curvature, g.edges_begin(1234)->curvature);
  // Truncated, and not a graph at all: the error names the file.
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = ::testing::TempDir() + "/cut.byrg";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  try {
    RoadGraph::load(cut);
    FAIL() << "a truncated file loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(cut), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("damaged or cut short"), std::string::npos) << e.what();
  }
  // One bit flipped anywhere: refused by the digest (14 of 53 such files loaded before).
  for (std::size_t at : {std::size_t{9}, bytes.size() / 3, bytes.size() / 2, bytes.size() - 20, bytes.size() - 1}) {
    std::string flipped = bytes;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
    const std::string ff = ::testing::TempDir() + "/flipped.byrg";
    std::ofstream(ff, std::ios::binary) << flipped;
    try {
      RoadGraph::load(ff);
      ADD_FAILURE() << "a file with a bit flipped at byte " << at << " loaded";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("digest does not match"), std::string::npos) << e.what();
    }
  }
  const std::string junk = ::testing::TempDir() + "/junk.byrg";
  std::ofstream(junk) << "x_m,y_m\n1,2\n";
  EXPECT_THROW(RoadGraph::load(junk), std::runtime_error);
  // An edge pointing past the last node.
  std::string bad = bytes;
  const std::size_t last_edge = bad.size() - 8 - sizeof(RoadGraph::Edge);
  const std::uint32_t far = 0xFFFFFFF0u;
  bad.replace(last_edge, 4, reinterpret_cast<const char*>(&far), 4);
  const std::string badf = ::testing::TempDir() + "/bad.byrg";
  std::ofstream(badf, std::ios::binary) << resealed(bad);
  EXPECT_THROW(RoadGraph::load(badf), std::runtime_error);
}

TEST(RoadGraph, TooNarrowTrackNamesWhere) {
  const TrackRoom narrow = [](double s) { return s > 300 && s < 320 ? std::make_pair(-1.0, 1.0) : std::make_pair(-7.0, 7.0); };
  try {
    RoadGraph::build(stadium(), narrow, RoadGraphParams{});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at s = 310.0 m"), std::string::npos) << e.what();
  }
}

TEST(GraphSearch, StaysOnTheLineWithoutObstaclesAndGoesRoundOne) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  GraphSearch search(g);
  SearchParams p;
  const std::uint32_t start = g.nearest_node(g.layer_at_or_after(50), 0);
  Plan clear = search.plan(start, {}, p);
  ASSERT_TRUE(clear.found);
  for (auto n : clear.nodes) EXPECT_EQ(g.node_d(n), 0.0);
  EXPECT_GE(g.node_s(clear.nodes.back()) - g.node_s(start), p.horizon);
  // A pylon on the line 150 m on: passed with the clearance, every edge checked.
  const FrenetObstacle pylon{g.node_s(start) + 150, 0.0, 0.3};
  Plan around = search.plan(start, {pylon}, p);
  ASSERT_TRUE(around.found);
  double least = 1e9, widest = 0;
  for (std::size_t i = 1; i < around.nodes.size(); ++i) {
    const double sa = g.node_s(around.nodes[i - 1]) - g.node_s(start), sb = g.node_s(around.nodes[i]) - g.node_s(start);
    const EdgeShape e{sa, g.node_d(around.nodes[i - 1]), sb, g.node_d(around.nodes[i])};
    FrenetObstacle rel = pylon;
    rel.s -= g.node_s(start);
    double gap;
    EXPECT_FALSE(edge_blocked(e, rel, g.params().half_width, p, &gap));
    least = std::min(least, gap);
    widest = std::max(widest, std::abs(e.d_b));
  }
  EXPECT_GE(least, p.clearance);
  EXPECT_LT(least, p.soft_clearance + 1.0);  // not needlessly wide
  EXPECT_EQ(g.node_d(around.nodes.back()), 0.0);  // back on the line by the horizon
  EXPECT_GT(around.cost, clear.cost);
  // A wall of pylons across the whole road: no route.
  std::vector<FrenetObstacle> wall;
  for (double d = -7; d <= 7; d += 1) wall.push_back({g.node_s(start) + 150, d, 0.5});
  EXPECT_FALSE(search.plan(start, wall, p).found);
}

// The curvature a lane change may have follows the car's speed (curvature_limit car): a pylon
// 35 m ahead on a straight is passed with a sharp swerve at 20 m/s; at 80 m/s, braking at
// 10 m/s^2, the car can be no slower than 75 m/s there and no swerve in 35 m asks less than
// 20 m/s^2 of it: no route (the planner stops for it), where the constant limit alone would
// have taken a swerve the car cannot drive.
TEST(GraphSearch, TheCarsSpeedLimitsTheCurvatureOfALaneChange) {
  const RefLine line = stadium();
  RoadGraphParams gp;
  gp.max_curvature = 0.1;  // the car's steering: the graph holds sharp edges
  const RoadGraph g = RoadGraph::build(line, kRoom, gp);
  GraphSearch search(g);
  const std::uint32_t start = g.nearest_node(g.layer_at_or_after(50), 0);
  const FrenetObstacle pylon{g.node_s(start) + 35, 0.0, 0.3};
  auto sharpest = [&](const Plan& plan, const SearchParams& p) {  // max over lane changes of kappa v^2
    double worst = 0;
    for (std::size_t i = 1; i < plan.nodes.size(); ++i) {
      const std::uint32_t a = plan.nodes[i - 1], b = plan.nodes[i];
      if (g.node_d(a) == g.node_d(b)) continue;
      for (const auto* e = g.edges_begin(a); e != g.edges_end(a); ++e)
        if (e->to == b) worst = std::max(worst, e->max_kappa * reachable_speed2(p, g.node_s(a) - g.node_s(start)));
    }
    return worst;
  };
  SearchParams slow;
  slow.lateral_accel = 20;
  slow.speed = 20;
  const Plan at20 = search.plan(start, {pylon}, slow);
  ASSERT_TRUE(at20.found);
  EXPECT_LE(sharpest(at20, slow), 20.0);
  SearchParams fast = slow;
  fast.speed = 80;
  const Plan at80 = search.plan(start, {pylon}, fast);
  EXPECT_FALSE(at80.found);
  SearchParams unlimited = fast;
  unlimited.lateral_accel = 0;  // the constant limit alone: a swerve the car could not drive at 80 m/s
  const Plan free = search.plan(start, {pylon}, unlimited);
  ASSERT_TRUE(free.found);
  EXPECT_GT(sharpest(free, fast), 20.0);
}

TEST(RoadGraphPlanner, CommitsToItsLastPlanAndRestartsWhenOffIt) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  PlannerParams pp;
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), pp);
  // A pylon on the straight, 0.5 m left of the line: planned around once seen in 3 frames.
  for (int k = 0; k < pp.confirmations; ++k) planner.observe({{150, 0.5, 0.3, 0}}, 0);
  const PlannedPath first = planner.plan(20, 0, 30);
  ASSERT_TRUE(first.route_found);
  EXPECT_TRUE(first.restarted);
  // 1.5 m (one cycle at 30 m/s) later the car is on the plan: it keeps it, so the two paths agree
  // where they overlap up to the commitment point.
  const PlannedPath second = planner.plan(21.5, 0, 30);
  EXPECT_FALSE(second.restarted);
  int same = 0;
  for (const auto& a : second.points)
    for (const auto& b : first.points)
      if (std::abs(a.s - b.s) < 1e-9) { EXPECT_NEAR(a.d, b.d, 1e-9); ++same; }
  EXPECT_GT(same, 10);
  // Far off the plan: start afresh from the car.
  EXPECT_TRUE(planner.plan(25, 4, 30).restarted);
  // Speeds: within the reference and the bends' limits.
  for (double v : second.speed) EXPECT_LE(v, 40.0 + 1e-9);
  // Forgetting: the pylon is dropped after obstacle_memory seconds unseen.
  planner.observe({}, static_cast<std::int64_t>((pp.obstacle_memory + 0.1) * 1e9));
  EXPECT_TRUE(planner.obstacles().empty());
}

TEST(SpeedProfile, CornerSpeedsDragAndTheEllipse) {
  // A 2 km straight, then a curve of radius 100 m, then the straight again (closed).
  std::vector<double> ds(600, 5.0), k(600, 0.0);
  for (int i = 400; i < 450; ++i) k[i] = 0.01;
  VehicleLimits l;
  l.v_max = 200;
  l.a_lat = 16;
  std::vector<double> v = speed_profile(ds, k, l, true);
  EXPECT_NEAR(v[425], 40.0, 1e-9);  // sqrt(16 / 0.01)
  // Drag and power bound the top speed: push = power / v meets drag · v² at (power/drag)^(1/3).
  l.drag = 1.0 / 2000;
  l.power = 600;
  v = speed_profile(ds, k, l, true);
  const double terminal = std::cbrt(l.power / l.drag);
  double top = 0;
  for (double x : v) top = std::max(top, x);
  EXPECT_LT(top, terminal);
  EXPECT_GT(top, 0.9 * terminal);
  // With the ellipse, no push is left at the corner's limit: drag alone acts through it.
  EXPECT_LE(v[430], 40.0 + 1e-9);
  EXPECT_LE(v[440], v[430] + 1e-9);
  l.ellipse = false;
  EXPECT_GT(speed_profile(ds, k, l, true)[440], v[440]);
  // Open profile from a given speed: brakes from it, not from the cap.
  std::vector<double> dso(99, 5.0), ko(100, 0.0);
  ko[99] = 0.01;
  const std::vector<double> vo = speed_profile(dso, ko, l, false, 30, 0);
  EXPECT_DOUBLE_EQ(vo[0], 30);
  EXPECT_DOUBLE_EQ(vo[99], 0);
  EXPECT_GT(profile_time(dso, vo, false), 0);
}

// The ggv's exponent below 2 cuts only the combined corners: the corner's own speed (pure lateral)
// and the straights' top speed stay; braking into the corner starts earlier (slower on the way in).
TEST(SpeedProfile, AnExponentBelowTwoCutsOnlyTheCombinedCorners) {
  std::vector<double> ds(600, 5.0), k(600, 0.0);
  for (int i = 400; i < 450; ++i) k[i] = 0.01;
  for (int i = 380; i < 400; ++i) k[i] = 0.01 * (i - 380) / 20.0;  // a clothoid entry: turning while braking
  VehicleLimits l;
  l.v_max = 60;
  l.a_lat = 16;
  const std::vector<double> ellipse = speed_profile(ds, k, l, true);
  l.ellipse_exponent = 2;
  EXPECT_EQ(speed_profile(ds, k, l, true), ellipse);
  l.ellipse_exponent = 1.6;
  const std::vector<double> cut = speed_profile(ds, k, l, true);
  EXPECT_NEAR(cut[425], 40.0, 1e-9);          // the corner's limit
  EXPECT_NEAR(cut[150], ellipse[150], 1e-9);  // the straight's top speed
  bool slower = false;
  for (std::size_t i = 0; i < cut.size(); ++i) {
    EXPECT_LE(cut[i], ellipse[i] + 1e-9) << i;
    slower = slower || cut[i] < ellipse[i] - 0.1;
  }
  EXPECT_TRUE(slower) << "braking while turning into the corner is planned with less grip";
  for (int i = 385; i < 396; ++i) EXPECT_LT(cut[i], ellipse[i]) << i;
}

}  // namespace

namespace {

// Drives a point car along each plan for dt at the plan's speed (braking at most 12 m/s²,
// accelerating at most 8), from x0 on the stadium's first straight; returns the largest x
// reached and the final speed. `late`: obstacles the planner is told of only from time t_seen.
struct Drive {
  double x_max = 0, v_end = 0;
  bool always_clear = true;  // no plan came within the clearance of an obstacle it knew
  int no_route = 0;
};
Drive drive(RoadGraphPlanner& planner, const RoadGraph& g, double x0, double v0, const std::vector<MapObstacle>& obstacles,
            double t_seen, double seconds) {
  Drive r;
  double x = x0, y = 0, v = v0;
  const double dt = 0.05;
  for (double t = 0; t < seconds; t += dt) {
    planner.observe(t >= t_seen ? obstacles : std::vector<MapObstacle>{}, static_cast<std::int64_t>(t * 1e9));
    const PlannedPath& p = planner.plan(x, y, v);
    r.no_route += !p.route_found;
    if (p.points.size() < 2) break;
    for (const auto& q : p.points)
      for (const auto& o : planner.obstacles())
        if (o.seen >= PlannerParams{}.confirmations && std::abs(q.x - o.x) < 1.0 + o.radius &&
            std::abs(q.y - o.y) < o.radius + g.params().half_width + 1.0 && q.s < 1e9)
          r.always_clear = false;
    // The car's place on the path, its target speed there, and a step along the path.
    std::size_t i = 0;
    double best = 1e18;
    for (std::size_t k = 0; k < p.points.size(); ++k) {
      const double d = std::hypot(p.points[k].x - x, p.points[k].y - y);
      if (d < best) { best = d; i = k; }
    }
    // Brake for what comes, as the path tracker does: the slowest point of the next 3 s, eased
    // by the distance to it at 12 m/s².
    double target = p.speed[i], ahead = 0;
    if (i + 1 < p.points.size()) {  // measured from the car, which may be past point i
      const double tx = p.points[i + 1].x - p.points[i].x, ty = p.points[i + 1].y - p.points[i].y, tl = std::hypot(tx, ty);
      if (tl > 0) ahead = -((x - p.points[i].x) * tx + (y - p.points[i].y) * ty) / tl;
    }
    for (std::size_t k = i + 1; k < p.points.size() && ahead < 3 * v + 1; ++k) {
      ahead += std::hypot(p.points[k].x - p.points[k - 1].x, p.points[k].y - p.points[k - 1].y);
      target = std::min(target, std::sqrt(p.speed[k] * p.speed[k] + 2 * 12 * ahead));
    }
    v = target < v ? std::max(target, v - 12 * dt) : std::min(target, v + 8 * dt);
    double go = v * dt;
    while (go > 0 && i + 1 < p.points.size()) {
      const double seg = std::hypot(p.points[i + 1].x - x, p.points[i + 1].y - y);
      if (seg >= go) {
        x += go * (p.points[i + 1].x - x) / seg;
        y += go * (p.points[i + 1].y - y) / seg;
        go = 0;
      } else {
        go -= seg;
        x = p.points[i + 1].x;
        y = p.points[i + 1].y;
        ++i;
      }
    }
    r.x_max = std::max(r.x_max, x);
  }
  r.v_end = v;
  return r;
}

TEST(RoadGraphPlanner, StopsBeforeARoadBlockedFromEdgeToEdge) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  std::vector<MapObstacle> wall;
  for (double d = -7; d <= 7; d += 0.5) wall.push_back({400, d, 0.3, 0});
  const Drive r = drive(planner, g, 100, 30, wall, 0, 30);
  EXPECT_GT(r.no_route, 0);
  EXPECT_LT(r.v_end, 0.5);                                      // it stopped
  EXPECT_LT(r.x_max + 4.0, 400 - 0.3);                          // its front short of the wall
  EXPECT_GT(r.x_max, 300);                                      // near it, not at its commitment
}

TEST(RoadGraphPlanner, AnObstacleSeenInsideTheCommitmentIsAvoidedOrStoppedFor) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  for (double ahead : {33.0, 60.0}) {
    RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 60.0), PlannerParams{});
    // Seen 0.5 s in, when the car (50 m/s, from x = 100) is `ahead` m short of it.
    const double x_obs = 100 + 25 + ahead;
    const Drive r = drive(planner, g, 100, 50, {{x_obs, 0, 0.3, 0}}, 0.5, 6);
    EXPECT_TRUE(r.always_clear) << ahead;
    EXPECT_GT(r.x_max, x_obs + 20) << ahead;  // and it went past
  }
}

TEST(RoadGraphPlanner, OneFramesFalseDetectionDoesNotCloseTheRoad) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  std::vector<MapObstacle> wall;
  for (double d = -7; d <= 7; d += 0.5) wall.push_back({200, d, 0.3, 0});
  planner.observe(wall, 0);  // seen in one frame only
  EXPECT_TRUE(planner.plan(100, 0, 30).route_found);
  planner.observe(wall, 50000000);
  planner.observe(wall, 100000000);  // the third frame: now it is real
  EXPECT_FALSE(planner.plan(101.5, 0, 30).route_found);
}

TEST(RoadGraph, RejectsFilesThatWouldBreakTheSearch) {
  const RoadGraph g = RoadGraph::build(stadium(), kRoom, RoadGraphParams{});
  const std::string path = ::testing::TempDir() + "/ok.byrg";
  g.save(path);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t edges_at = bytes.size() - 8 - g.edge_count() * sizeof(RoadGraph::Edge);
  auto expect_refused = [&](std::string b, const char* why) {
    const std::string f = ::testing::TempDir() + "/crafted.byrg";
    std::ofstream(f, std::ios::binary) << resealed(b);
    try {
      RoadGraph::load(f);
      ADD_FAILURE() << "loaded: " << why;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  // Edge 0 (of node 0) turned back to node 0 itself: a cycle.
  std::string back = bytes;
  const std::uint32_t zero = 0;
  back.replace(edges_at, 4, reinterpret_cast<const char*>(&zero), 4);
  expect_refused(back, "does not lead 1 to 8 layers forward");
  // A negative curvature cost.
  std::string neg = bytes;
  const float minus = -1e6f;
  neg.replace(edges_at + 8, 4, reinterpret_cast<const char*>(&minus), 4);
  expect_refused(neg, "negative or non-finite cost");
  // A lateral step of zero in the parameters.
  std::string step0 = bytes;
  const double nil = 0;
  step0.replace(8 + 3 * sizeof(double), sizeof(double), reinterpret_cast<const char*>(&nil), sizeof(double));
  expect_refused(step0, "lateral_step = 0 is outside");
  // Node 0's edge range running past the edges, the next node's back inside them (found by
  // fuzz_road_graph: the edges were read before the ranges were checked, beyond the array).
  std::string past = bytes;
  const std::size_t first_edges_at = edges_at - 8 - (g.node_count() + 1) * sizeof(std::uint32_t);
  const std::uint32_t beyond = static_cast<std::uint32_t>(g.edge_count() + 1000);
  past.replace(first_edges_at + 4, 4, reinterpret_cast<const char*>(&beyond), 4);
  expect_refused(past, "edge ranges out of order at node 1");
}

TEST(RoadGraph, BuildRefusesParametersOutOfRange) {
  RoadGraphParams p;
  p.layer_spacing = 1e300;
  EXPECT_THROW(RoadGraph::build(stadium(), kRoom, p), std::invalid_argument);
  p = RoadGraphParams{};
  p.lateral_step = 1e-12;
  EXPECT_THROW(RoadGraph::build(stadium(), kRoom, p), std::invalid_argument);
  const TrackRoom nan_room = [](double) { return std::make_pair(std::nan(""), 7.0); };
  EXPECT_THROW(RoadGraph::build(stadium(), nan_room, RoadGraphParams{}), std::invalid_argument);
}

}  // namespace

// The adapter's geometry (plan_frames.hpp): obstacles into the map with the pose of their stamp,
// and a plan as a Path's poses.
TEST(PlanFrames, ObstaclesIntoTheMapFrame) {
  const StampedPose car{0, 10, 20, M_PI / 2};  // facing +y
  const auto m = obstacle_in_map(car, 5, 1, 0.4, 0.6);  // 5 m ahead, 1 m left
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->x, 9, 1e-12);
  EXPECT_NEAR(m->y, 25, 1e-12);
  EXPECT_DOUBLE_EQ(m->radius, 0.3);
  EXPECT_DOUBLE_EQ(obstacle_in_map(car, 1, 0, 0.01, 0.01)->radius, 0.1);  // at least 0.1 m
  EXPECT_DOUBLE_EQ(obstacle_in_map(car, 1, 0, NAN, 1)->radius, 5.0);     // unknown size: blocks
  EXPECT_FALSE(obstacle_in_map(car, NAN, 0, 1, 1).has_value());
  EXPECT_FALSE(obstacle_in_map({0, 1e308, 0, 0}, 1e308, 0, 1, 1).has_value());  // overflows
}

// The edge band widens with the spread of a detection's place: the pose's, and its heading's
// times the range.
TEST(PlanFrames, PlacementBandGrowsWithRangeAndTheEstimatesSpread) {
  const StampedPose sure{0, 0, 0, 0, 0, 0};
  EXPECT_DOUBLE_EQ(placement_band(sure, 200, 0, 1.0, 2), 1.0);
  const StampedPose pose{0, 0, 0, 0, 0.01, 0.003};
  EXPECT_NEAR(placement_band(pose, 200, 0, 1.0, 2), 1.0 + 2 * (0.01 + 0.6), 1e-12);
  EXPECT_NEAR(placement_band(pose, 30, 40, 1.0, 2), 1.0 + 2 * (0.01 + 0.15), 1e-12);  // range 50 m
  EXPECT_DOUBLE_EQ(placement_band(pose, 200, 0, 1.0, 0), 1.0);
  EXPECT_DOUBLE_EQ(placement_band({0, 0, 0, 0, NAN, 0.003}, 200, 0, 1.0, 2), 1.0);  // judged as placed
  // A wall stripe seen 200 m off, 1.04 m inside the left edge of a ring 8 m wide each side
  // (radius 1 km, anticlockwise: the left edge is the inner one): taken as on the track by the
  // bare band, not once the heading's spread is counted.
  brickyard::track::CenterLine ring;
  for (int i = 0; i < 2000; ++i) {
    ring.x.push_back(1000 * std::cos(2 * M_PI * i / 2000));
    ring.y.push_back(1000 * std::sin(2 * M_PI * i / 2000));
    ring.width_left.push_back(8);
    ring.width_right.push_back(8);
  }
  const brickyard::track::Track track({"ring", ring, {}});
  const double band = placement_band(pose, 200, 0, 1.0, 2);
  EXPECT_TRUE(on_track(track, 1000 - 8 + 1.04, 0, 1.0));
  EXPECT_FALSE(on_track(track, 1000 - 8 + 1.04, 0, band));
  EXPECT_TRUE(on_track(track, 1000, 0, band));  // a pylon on the centre line still is
}

TEST(PlanFrames, PathGeometryHeadingAndArcLength) {
  const std::vector<PathSample> pts{{0, 0, 0, 0.5, 0.01}, {3, 4, 5, -1.5, 0.02}, {3, 10, 11, 0, 0}};
  const PathGeometry g = path_geometry(pts);
  ASSERT_EQ(g.x.size(), 3u);
  EXPECT_DOUBLE_EQ(g.yaw[0], std::atan2(4.0, 3.0));
  EXPECT_DOUBLE_EQ(g.yaw[2], M_PI / 2);  // the last looks back at the one before
  EXPECT_DOUBLE_EQ(g.s[1], 5);
  EXPECT_DOUBLE_EQ(g.s[2], 11);
  EXPECT_EQ(g.curvature, (std::vector<double>{0.01, 0.02, 0}));
  EXPECT_DOUBLE_EQ(g.max_offset, 1.5);
  EXPECT_TRUE(path_geometry({}).x.empty());
}

namespace {

// The least gap between the car's side and an obstacle at (x_o, d_o) on the stadium's first
// straight (where the line is y = 0), over the path points where the car is beside it (its
// reference point from car_front + radius before to car_rear + radius past it).
double side_gap(const PlannedPath& p, double x_o, double d_o, double radius, double half_width) {
  const SearchParams sp;
  double gap = 1e9;
  for (const auto& q : p.points)
    if (q.x >= x_o - sp.car_front - radius && q.x <= x_o + sp.car_rear + radius)
      gap = std::min(gap, std::abs(q.y - d_o) - half_width - radius);
  return gap;
}

// The car driven along its plans on the first straight, 1.5 m a cycle, from x0 to x1.
void drive_on(RoadGraphPlanner& planner, double x0, double x1, double v, double& y) {
  for (double x = x0; x <= x1; x += 1.5) {
    const PlannedPath& p = planner.plan(x, y, v);
    for (std::size_t k = 1; k < p.points.size(); ++k)
      if (p.points[k].x >= x + 1.5) {
        y = p.points[k - 1].y + (p.points[k].y - p.points[k - 1].y) * (x + 1.5 - p.points[k - 1].x) /
                                    (p.points[k].x - p.points[k - 1].x);
        break;
      }
  }
}

}  // namespace

// A pylon's place moves by centimetres from detection to detection. A swerve planned at the full
// clearance is kept while the obstacle stays beyond keep_clearance, and dropped nearer than that.
TEST(RoadGraphPlanner, AnObstacleThatMovesByCentimetresKeepsThePlan) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  PlannerParams pp;
  pp.obstacle_drift = 100;  // each detection taken as it comes: the place moves with it (fusing: below)
  const double hw = g.params().half_width, r = 0.3;
  for (double moved : {0.3, 0.7}) {  // gap 1.5+ less this: kept above 1.0, dropped below
    RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), pp);
    for (int k = 0; k < pp.confirmations; ++k) planner.observe({{150, 0.5, r, 0}}, 0);
    double y = 0;
    drive_on(planner, 20, 128, 30, y);
    const PlannedPath& before = planner.plan(129.5, y, 30);
    const double gap = side_gap(before, 150, 0.5, r, hw);
    ASSERT_GE(gap, pp.search.clearance - 1e-6);
    double d_near = 0;  // the path's side of the pylon
    for (const auto& q : before.points)
      if (std::abs(q.x - 150) < 1) d_near = q.y;
    // Toward the path, to `moved` inside the clearance.
    const double shifted = 0.5 + (d_near > 0.5 ? 1 : -1) * (moved + gap - pp.search.clearance);
    // Detection by detection, a few centimetres at a time (each within merge_distance: the same pylon).
    const int steps = 1 + static_cast<int>(std::abs(shifted - 0.5) / 0.1);
    for (int k = 1; k <= steps; ++k) planner.observe({{150, 0.5 + (shifted - 0.5) * k / steps, r, 0}}, 50000000 * k);
    ASSERT_EQ(planner.obstacles().size(), 1u);
    const PlannedPath& after = planner.plan(131, y, 30);
    const bool kept = pp.search.clearance - moved >= pp.keep_clearance;
    EXPECT_EQ(after.restarted, !kept) << "moved " << moved;
    if (kept) EXPECT_NEAR(side_gap(after, 150, shifted, r, hw), pp.search.clearance - moved, 0.05);
  }
}

// A pylon seen from afar, its place jumping sideways with the estimate's heading (half a metre
// at 100 m): the remembered place is the detections fused by their spread, so it stays within a
// few centimetres of the pylon, and a near detection (small spread) outweighs the far ones. A
// place that really moves is followed, at obstacle_drift.
TEST(RoadGraphPlanner, FarDetectionsAreFusedByTheirSpread) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  PlannerParams pp;
  pp.obstacle_fusion = true;
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), pp);
  const double far = 0.25, near = 0.01;  // variances, m²: 0.5 m and 0.1 m
  std::int64_t t = 0;
  auto seen = [&](double y, double var) {
    MapObstacle o{150, y, 0.3, 0, 0};
    o.variance = var;
    planner.observe({o}, t += 50000000);
    return planner.obstacles().at(0).y;
  };
  double worst = 0, last = 0;
  for (int k = 0; k < 20; ++k) {
    last = seen(k % 2 ? 0.5 : -0.5, far);  // truth: y = 0
    if (k >= 3) worst = std::max(worst, std::abs(last));
  }
  EXPECT_LT(worst, 0.3);  // each detection alone: 0.5 off
  EXPECT_EQ(planner.obstacles().size(), 1u);
  const double after_near = seen(0.05, near);
  EXPECT_NEAR(after_near, 0.05, 0.05) << "a near detection outweighs the far ones (before it: " << last << ")";
  // It moves 1 m sideways and stays: followed within a second and a half.
  double y = 0;
  for (int k = 0; k < 30; ++k) y = seen(1.05, near);
  EXPECT_NEAR(y, 1.05, 0.05);
  // An unknown spread (not a number) is a metre: it neither breaks the place nor moves it far.
  y = seen(std::nan(""), std::nan(""));
  EXPECT_TRUE(std::isfinite(planner.obstacles().at(0).y));
}

// No route, no full swerve the car can steer at its speed, and no room to stop before the pylon:
// the car swerves as far from it as it can steer, braking (the least harm), instead of braking
// straight at it. A car that can stop before it stops.
TEST(RoadGraphPlanner, WithNoRoomToStopTheCarSwervesAsFarAsItCan) {
  const RefLine line = stadium();
  const TrackRoom narrow = [](double) { return std::make_pair(-4.1, 4.1); };
  const RoadGraph g = RoadGraph::build(line, narrow, RoadGraphParams{});
  PlannerParams pp;
  pp.search.lateral_accel = 1.0;  // m/s²: the full lane change (2.2 m in 165 m) is too sharp at 55 m/s and up
  const double r = 0.1, hw = g.params().half_width;
  auto plan_at = [&](double speed) {
    auto planner = std::make_unique<RoadGraphPlanner>(g, line, std::vector<double>(line.size(), 80.0), pp);
    for (int k = 0; k < pp.confirmations; ++k) planner->observe({{300, 0, r, 0}}, 0);
    PlannedPath p = planner->plan(130, 0, speed);
    return p;
  };
  const PlannedPath fast = plan_at(80);  // braking needs 80² / 24 = 267 m; the pylon is 165 m ahead
  EXPECT_FALSE(fast.route_found);
  ASSERT_TRUE(fast.swerve);
  EXPECT_TRUE(fast.swerve_short);
  double beside = 0, kv2 = 0;
  for (std::size_t i = 0; i < fast.points.size(); ++i) {
    const auto& q = fast.points[i];
    if (std::abs(q.x - 300) < 1.5) beside = std::abs(q.y);
    // At most the speed the car can brake to by there (the swerve is judged at the speeds it
    // brakes to within the grip its bends leave, never lower than braking at full a_decel).
    if (q.x > 130 && q.x < 290) kv2 = std::max(kv2, std::abs(q.kappa) * std::max(0.0, 80 * 80 - 2 * pp.limits.a_decel * (q.x - 130)));
    EXPECT_LE(std::abs(q.d), 4.1 - hw - pp.swerve_edge_margin + 1e-6) << "at s " << q.s;
  }
  EXPECT_GT(beside, 0.3) << "moved off the pylon's line";
  EXPECT_LT(beside - hw - r, pp.keep_clearance) << "short of the full clearance (that one is not steerable)";
  EXPECT_LE(kv2, pp.search.lateral_accel * 1.05) << "steerable at the speeds the car brakes to";
  const PlannedPath slow = plan_at(55);  // stops in 126 m: brakes straight
  EXPECT_FALSE(slow.swerve);
}

// With no route, the path the car brakes along keeps inside the track, even where the racing
// line runs near the edge the car is on (a parallel to the line would leave the track there).
TEST(RoadGraphPlanner, WithNoRouteThePathStaysOnTheTrack) {
  const RefLine line = stadium();
  // 7 m each side, then from s = 250 only 3 m on the left.
  const TrackRoom room = [](double s) { return std::make_pair(-7.0, s < 250 ? 7.0 : 3.0); };
  const RoadGraph g = RoadGraph::build(line, room, RoadGraphParams{});
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  std::vector<MapObstacle> wall;
  for (double d = -7; d <= 7; d += 0.5) wall.push_back({400, d, 0.3, 0});
  for (int k = 0; k < PlannerParams{}.confirmations; ++k) planner.observe(wall, 0);
  const double left = 7 - g.params().half_width - g.params().edge_margin;  // the band's left edge before 250
  const PlannedPath& p = planner.plan(100, left, 30);
  ASSERT_FALSE(p.route_found);
  const double band = 3 - g.params().half_width - g.params().edge_margin;
  int checked = 0;
  for (const auto& q : p.points)
    if (q.s >= 265 && q.s <= 600) {
      EXPECT_LE(q.d, band + 1e-9) << "at s " << q.s;
      ++checked;
    }
  EXPECT_GT(checked, 50);
  // A car placed 20 m off the line, beyond the edge, is not there (its estimate drifted): the
  // path keeps its offset, the line's shape, rather than steering it across what it takes for the
  // track.
  RoadGraphPlanner lost(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  for (int k = 0; k < PlannerParams{}.confirmations; ++k) lost.observe(wall, 0);
  const PlannedPath& q = lost.plan(100, 20, 30);
  ASSERT_FALSE(q.route_found);
  for (const auto& pt : q.points) EXPECT_NEAR(pt.d, 20, 1e-9) << "at s " << pt.s;
}

// A pylon in the middle of an 8.2 m road: the graph's nodes keep the car's side edge_margin
// (1.5 m) from the edges, so none lies beside it at any clearance. The car swerves past it,
// braking, at keep_clearance and no nearer the edge than swerve_edge_margin (Monza, s = 3764 m).
TEST(RoadGraphPlanner, WithNoNodeBesideAnObstacleTheCarSwervesPastIt) {
  const RefLine line = stadium();
  const TrackRoom narrow = [](double) { return std::make_pair(-4.1, 4.1); };
  const RoadGraph g = RoadGraph::build(line, narrow, RoadGraphParams{});
  PlannerParams pp;
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 80.0), pp);
  const double r = 0.1, hw = g.params().half_width;
  for (int k = 0; k < pp.confirmations; ++k) planner.observe({{300, 0, r, 0}}, 0);
  const PlannedPath& p = planner.plan(130, 0, 80);
  EXPECT_FALSE(p.route_found);
  ASSERT_TRUE(p.swerve);
  const SearchParams sp;
  for (const auto& q : p.points) {
    EXPECT_LE(std::abs(q.d), 4.1 - hw - pp.swerve_edge_margin + 1e-6) << "at s " << q.s;
    if (q.x >= 300 - sp.car_front - r && q.x <= 300 + sp.car_rear + r)
      EXPECT_GE(std::abs(q.y) - hw - r, pp.keep_clearance) << "beside the pylon at s " << q.s;
  }
  double at_pylon = 0;  // braking: slower there than the car is now
  for (std::size_t i = 0; i < p.points.size(); ++i)
    if (std::abs(p.points[i].x - 300) < 1.5) at_pylon = p.speed[i];
  EXPECT_GT(at_pylon, 0);
  EXPECT_LT(at_pylon, 60);
  // The road blocked from edge to edge: no swerve, the car stops (StopsBeforeARoadBlockedFromEdgeToEdge).
  RoadGraphPlanner blocked(g, line, std::vector<double>(line.size(), 80.0), pp);
  std::vector<MapObstacle> wall;
  for (double d = -4; d <= 4; d += 0.5) wall.push_back({300, d, 0.3, 0});
  for (int k = 0; k < pp.confirmations; ++k) blocked.observe(wall, 0);
  EXPECT_FALSE(blocked.plan(130, 0, 80).swerve);
}

// A pylon on the line in a hairpin (15 m radius) of a 9.2 m road, no node beside it at any
// clearance: the emergency swerve past it counts the car's sweep in the bend (its nose
// swings out 0.5 m there) and passes it at keep_clearance, swept side and all. (Spielberg's
// hairpin, s = 1400 m: judged as if the car went straight, every swerve came out short of
// keep_clearance once its shape was checked, and the car, unable to stop in the bend, rolled by
// 0.499 m off.)
TEST(RoadGraphPlanner, ASwerveInAHairpinCountsTheSweepOfTheBend) {
  const double radius = 15;
  const RefLine line = stadium(radius);
  const TrackRoom narrow = [](double) { return std::make_pair(-4.6, 4.6); };
  RoadGraphParams gp;
  gp.max_curvature = 0.1;  // the AV-21's steering, as curvature_limit car has it
  const RoadGraph g = RoadGraph::build(line, narrow, gp);
  PlannerParams pp;
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 12.0), pp);
  const double r = 0.15, d_pylon = 0, hw = g.params().half_width;
  const Eigen::Vector2d at = line.point(600 + 0.5 * M_PI * radius, d_pylon);  // the middle of the hairpin
  for (int k = 0; k < pp.confirmations; ++k) planner.observe({{at.x(), at.y(), r, 0}}, 0);
  const PlannedPath& p = planner.plan(560, 0, 12);
  EXPECT_FALSE(p.route_found);
  ASSERT_TRUE(p.swerve);
  EXPECT_FALSE(p.swerve_short);
  const SearchParams sp;
  const double s_pylon = 600 + 0.5 * M_PI * radius;
  for (const auto& q : p.points)
    if (q.s >= s_pylon - sp.car_front - r && q.s <= s_pylon + sp.car_rear + r)
      EXPECT_GE(std::abs(q.d - d_pylon) - r - swept_half_width(hw, q.kappa, sp), pp.keep_clearance - 1e-6) << "beside the pylon at s " << q.s;
}

// A pylon hidden until 95 m ahead in a bend the car takes near its lateral limit (Monza's Lesmo
// behind its inner wall): the lane change round it is sharper than the car can steer at its speed
// now, but not at the speed it has there while it brakes within the grip its bend leaves. The
// swerve is judged by that, and passes at keep_clearance instead of least-harm short of it.
TEST(RoadGraphPlanner, ASwerveInABendIsJudgedAtTheSpeedTheCarBrakesTo) {
  const RefLine line = stadium();  // a 200 m radius turn from s = 600 m
  const TrackRoom narrow = [](double) { return std::make_pair(-4.1, 4.1); };
  const RoadGraph g = RoadGraph::build(line, narrow, RoadGraphParams{});
  PlannerParams pp;
  pp.search.lateral_accel = 20;  // m/s²: at 60 m/s the bend alone takes 18
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 80.0), pp);
  const double r = 0.1, hw = g.params().half_width, v = 60;
  const Eigen::Vector2d pylon = line.point(895, 0), car = line.point(800, 0);
  for (int k = 0; k < pp.confirmations; ++k) planner.observe({{pylon.x(), pylon.y(), r, 0}}, 0);
  const PlannedPath& p = planner.plan(car.x(), car.y(), v);
  EXPECT_FALSE(p.route_found);
  ASSERT_TRUE(p.swerve);
  EXPECT_FALSE(p.swerve_short) << "a full swerve, steerable at the speeds braked to";
  double kv2 = 0, gap = 1e9;
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const PathSample& q = p.points[i];
    kv2 = std::max(kv2, std::abs(q.kappa) * p.speed[i] * p.speed[i]);
    if (q.s >= 895 - SearchParams{}.car_front - r && q.s <= 895 + SearchParams{}.car_rear + r)
      gap = std::min(gap, std::abs(q.d) - hw - r);
  }
  EXPECT_GE(gap, pp.keep_clearance - 0.05) << "beside the pylon";
  EXPECT_LE(kv2, pp.search.lateral_accel * 1.05) << "the path's speeds keep within the car's lateral limit";
}

// A car that passed an obstacle near (under the clearance) and stopped just past it must start
// again: the path behind it is driven, the obstacle there blocks nothing. (On Spielberg's hairpin
// a car stopped 8 m past a pylon it had passed 0.57 m off stood for ever: every lead-in, path
// behind the car included, "hit" the pylon.)
TEST(RoadGraphPlanner, ACarStoppedJustPastAnObstacleDrivesOn) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  for (int k = 0; k < PlannerParams{}.confirmations; ++k) planner.observe({{300, 1.5, 0.2, 0}}, 0);
  const PlannedPath p = planner.plan(302.5, 0, 0);  // its rear 1.5 m past the pylon, 0.3 m beside it
  EXPECT_TRUE(p.route_found);
  double v_max = 0;
  for (std::size_t i = 0; i < p.points.size(); ++i) v_max = std::max(v_max, p.speed[i]);
  EXPECT_GT(v_max, 5.0) << "it drives on";
}

// A car that stopped beside an obstacle, nearer than the clearance (its body beside the pylon),
// drives away from it: a lead-in that takes it no nearer than it is is not blocked by it. (On
// Spielberg's hairpin a car braked to a stand 0.65 m beside a pylon and stood for ever: every
// lead-in starts at the car, and there the pylon was under the clearance.)
TEST(RoadGraphPlanner, ACarStoppedBesideAnObstacleDrivesAwayFromIt) {
  const RefLine line = stadium();
  const RoadGraph g = RoadGraph::build(line, kRoom, RoadGraphParams{});
  RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), PlannerParams{});
  for (int k = 0; k < PlannerParams{}.confirmations; ++k) planner.observe({{300, 1.5, 0.2, 0}}, 0);
  const PlannedPath p = planner.plan(299, 0, 0);  // its body beside the pylon, 0.33 m off
  ASSERT_TRUE(p.route_found);
  double v_max = 0, d_max = -1e9;
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    v_max = std::max(v_max, p.speed[i]);
    if (p.points[i].s < 305) d_max = std::max(d_max, p.points[i].d);
  }
  EXPECT_GT(v_max, 5.0) << "it drives on";
  EXPECT_LE(d_max, 1e-6) << "never nearer the pylon than it stood";
}

// A car standing beside the band where it narrows (it stopped there) has no lead-in sharp enough
// to the layer at the commitment distance; one to a layer farther on bends gently back in.
TEST(RoadGraphPlanner, ACarStoppedBesideTheBandRejoinsItFartherOn) {
  const RefLine line = stadium();
  const TrackRoom room = [](double s) { return std::make_pair(-7.0, s < 290 ? 7.0 : 0.5); };
  const RoadGraph g = RoadGraph::build(line, room, RoadGraphParams{});
  auto found = [&](double rejoin) {
    PlannerParams pp;
    pp.rejoin_reach = rejoin;
    RoadGraphPlanner planner(g, line, std::vector<double>(line.size(), 40.0), pp);
    return planner.plan(300, 5.5, 0).route_found;
  };
  EXPECT_FALSE(found(0)) << "the layer at the commitment distance is out of the car's steering";
  EXPECT_TRUE(found(PlannerParams{}.rejoin_reach));
}

// The planner's obstacles are placed with the pose at their stamp and the spreads of the nearer
// estimate (the history itself is tested in test_libs.cpp).
TEST(PlanFrames, PoseAtCarriesTheNearerEstimatesSpreads) {
  PoseHistory h(8);
  EXPECT_FALSE(pose_at(h, 0));
  h.add(0, {0.0, 0.0, 0.0}, {0.1, 0.01});
  h.add(8'000'000, {0.64, 0.08, 0.0}, {0.2, 0.02});
  const StampedPose p = *pose_at(h, 2'000'000);
  EXPECT_NEAR(p.x, 0.16, 1e-12);
  EXPECT_EQ(p.stamp_ns, 2'000'000);
  EXPECT_EQ(p.position_sigma, 0.1);
  EXPECT_EQ(p.yaw_sigma, 0.01);
  EXPECT_EQ(pose_at(h, 4'000'000)->position_sigma, 0.2);  // a tie: the newer's
  const StampedPose late = *pose_at(h, 9'000'000);
  EXPECT_EQ(late.x, 0.64);
  EXPECT_EQ(late.stamp_ns, 8'000'000);  // not interpolated: the estimate's own stamp
}

namespace {

// The stadium's centre line (as stadium()) as a track `width` m wide each side.
brickyard::track::CenterLine stadium_points(double width) {
  brickyard::track::CenterLine c;
  const double L = 600, r = 200;
  auto add = [&](double x, double y) {
    c.x.push_back(x);
    c.y.push_back(y);
    c.width_left.push_back(width);
    c.width_right.push_back(width);
  };
  auto arc = [&](double cx, double a0) {
    const int m = static_cast<int>(M_PI * r / 5);
    for (int i = 0; i < m; ++i) add(cx + r * std::cos(a0 + M_PI * i / m), r + r * std::sin(a0 + M_PI * i / m));
  };
  for (double s = 0; s < L; s += 5) add(s, 0);
  arc(L, -M_PI / 2);
  for (double s = L; s > 0; s -= 5) add(s, 2 * r);
  arc(0, M_PI / 2);
  return c;
}

// The stadium's centre line as a racing line file's.
LineSource stadium_source() {
  LineSource src;
  src.file_line = stadium_points(8);
  src.file_line.source = "stadium.csv";
  src.limits = brickyard::motion::independent_limits(40, 10, 5, 8);
  return src;
}

brickyard::vehicle::Vehicle test_car() {
  brickyard::vehicle::Vehicle car;
  car.half_width = 0.97;
  car.front = 4.0;
  car.rear = 1.0;
  car.wheelbase = 3.0;
  car.max_steer = 0.3;
  car.a_lat = 20;
  car.a_decel = 15;
  return car;
}

double metric(const std::vector<std::pair<std::string, double>>& m, const std::string& name) {
  for (const auto& [n, v] : m)
    if (n == name) return v;
  ADD_FAILURE() << "no metric " << name;
  return NAN;
}

}  // namespace

TEST(RoadGraphRun, TheCarsSizeAndSteeringUnlessTheGraphSaysOtherwise) {
  const brickyard::vehicle::Vehicle car = test_car();
  const VehicleLimits limits = brickyard::motion::independent_limits(40, 10, 5, 8);
  RoadGraphSettings s;
  s.car_front = 4.5;
  const RoadGraphConfig c = road_graph_config(s, car, limits);
  EXPECT_EQ(c.graph.half_width, 0.97);
  EXPECT_EQ(c.planner.search.car_front, 4.5);
  EXPECT_EQ(c.planner.search.car_rear, 1.0);
  EXPECT_EQ(c.planner.limits.v_max, limits.v_max);
  EXPECT_EQ(c.graph.max_curvature, RoadGraphParams{}.max_curvature);  // curvature_limit constant
  EXPECT_EQ(c.planner.search.lateral_accel, 0);
  s.car_curvature = true;
  const RoadGraphConfig k = road_graph_config(s, car, limits);
  EXPECT_DOUBLE_EQ(k.graph.max_curvature, std::tan(0.8 * 0.3) / 3.0);
  EXPECT_EQ(k.planner.search.lateral_accel, 20);
  EXPECT_EQ(k.planner.search.brake, 15);
  s.steer_margin = 0.1;
  brickyard::vehicle::Vehicle long_car = car;
  long_car.wheelbase = 1000;  // a turn wider than a kilometre: the graph keeps 0.001
  EXPECT_EQ(road_graph_config(s, long_car, limits).graph.max_curvature, 0.001);
}

TEST(RoadGraphRun, AGraphFileMustFitTheLineAndTheParameters) {
  const LineSource src = stadium_source();
  const RoadGraphParams p;
  const std::string path = ::testing::TempDir() + "/run_stadium.byrg";
  RoadGraph::build(stadium(), kRoom, p, reference_digest(src.file_line, src.edge_margin, p)).save(path);
  EXPECT_EQ(load_graph_file(path, src, p)->node_count(), RoadGraph::load(path).node_count());
  auto refused = [](const std::string& file, const LineSource& line, const RoadGraphParams& q) -> std::string {
    try {
      load_graph_file(file, line, q);
    } catch (const RoadGraphInputError& e) {
      return e.what();
    }
    return "loaded";
  };
  RoadGraphParams other = p;
  other.lateral_step = 1.0;
  EXPECT_EQ(refused(path, src, other), "graph_file " + path +
                                           " was built with other graph parameters than this node's (rebuild it with brickyard-plan "
                                           "graph and the same options)");
  LineSource wider = src;
  wider.edge_margin = 3.0;
  EXPECT_EQ(refused(path, wider, p), "graph_file " + path +
                                        " was built for another racing line, edge_margin or graph parameters (rebuild it with "
                                        "brickyard-plan graph)");
  const std::string missing = ::testing::TempDir() + "/no_such.byrg";
  EXPECT_EQ(refused(missing, src, p).rfind("graph_file ", 0), 0u) << refused(missing, src, p);
}

// Detections across the road, three frames running: the road is closed, said once an episode.
TEST(RoadGraphRun, PlacesDetectionsAndWarnsOnceAnEpisodeWithoutARoute) {
  const LineSource src = stadium_source();
  RoadGraphRun run(src, road_graph_config(RoadGraphSettings{}, test_car(), src.limits), nullptr, "");
  EXPECT_FALSE(run.started());
  const std::string said = run.start({"stadium", stadium_points(8), {}});
  EXPECT_TRUE(run.started());
  EXPECT_EQ(said.rfind("road graph built from the map: ", 0), 0u) << said;
  // 200 m ahead of the car at (100, 0) facing +x: 27 pylons from edge band to edge band, one
  // within the band (the wall) and one beyond the edge.
  std::vector<Detection> across;
  for (double y = -6.5; y <= 6.5; y += 0.5) across.push_back({200, y, 0.6, 0.6});
  across.push_back({200, 7.5, 0.6, 0.6});
  across.push_back({200, -9, 0.6, 0.6});
  const StampedPose car{0, 100, 0, 0};
  auto close_road = [&](std::int64_t from_ns) {
    for (int frame = 0; frame < 3; ++frame) {  // confirmed in the third
      std::vector<MapObstacle> seen;
      run.place(car, across, seen);
      EXPECT_EQ(seen.size(), 27u);
      run.observe(seen, from_ns + frame * 50'000'000);
    }
  };
  close_road(0);
  const std::optional<CyclePlan> first = run.plan(100, 0, 30);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->warning.rfind("no route: ", 0), 0u) << first->warning;
  EXPECT_NE(first->warning.find("obstacles: (s "), std::string::npos) << first->warning;
  EXPECT_EQ(first->speed.size(), first->path.x.size());
  const std::optional<CyclePlan> second = run.plan(101, 0, 29);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->warning, "") << "the same episode";
  EXPECT_FALSE(run.plan(NAN, 0, 30).has_value());
  // The obstacles forgotten, a route; closed again, a new episode.
  run.observe({}, 3'000'000'000);
  const std::optional<CyclePlan> open = run.plan(102, 0, 28);
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->warning, "");
  close_road(3'050'000'000);
  const std::optional<CyclePlan> again = run.plan(103, 0, 28);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->warning.rfind("no route: ", 0), 0u) << again->warning;

  const auto m = run.metrics(4);
  EXPECT_EQ(m.front().first, "plans");
  EXPECT_EQ(metric(m, "plans"), 4);
  EXPECT_EQ(metric(m, "plans_without_route"), 3);
  EXPECT_EQ(metric(m, "detections_off_track"), 12);
  EXPECT_EQ(metric(m, "obstacles_remembered_max"), 27);
  EXPECT_EQ(metric(m, "obstacles_planned_around_max"), 27);
  EXPECT_GT(metric(m, "planned_lap_s"), 0);
  EXPECT_EQ(m.back().first, "graph_edges");
  const LatticeDrawing lattice = run.lattice_near_obstacles();
  EXPECT_FALSE(lattice.x.empty());
  EXPECT_EQ(lattice.x.size(), lattice.y.size());
}

TEST(PlanFrames, DetectionsWithoutATrackAreAllPlacedAndSpreadsFromVariances) {
  std::vector<MapObstacle> seen;
  EXPECT_EQ(place_detections({0, 10, 20, 0}, {{5, 1, 0.4, 0.6}, {NAN, 0, 1, 1}}, nullptr, 1.0, 2.0, seen), 0u);
  ASSERT_EQ(seen.size(), 1u);  // the one not finite is no place
  EXPECT_EQ(seen[0].x, 15);
  EXPECT_EQ(seen[0].y, 21);
  const PoseSpread s = pose_spread(0.04, 0.09, -1);
  EXPECT_DOUBLE_EQ(s.position, 0.3);
  EXPECT_EQ(s.yaw, 0);
}
