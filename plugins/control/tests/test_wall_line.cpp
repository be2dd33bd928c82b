// Wall following on road courses (plugins/control/common/wall_line.hpp): which wall, the gap, the
// offset line, and the follower closed-loop on circular walls with a kinematic car.
#include "control/common/engagement.hpp"
#include "control/common/mapped_wall.hpp"
#include "control/common/wall_line.hpp"
#include "control/common/wall_line_run.hpp"
#include "control/vehicle_tracking.hpp"

#include "av21.hpp"
#include "shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace brickyard::control;

namespace {

WallView straight(double y0) { return {{y0, 0.0, 0.0}, true, -5, 20}; }

// Least-squares quadratic y(x) through points (the wall detector's fit, without the lean).
std::vector<double> fit_quadratic(const std::vector<std::array<double, 2>>& pts) {
  double a[3][4] = {};
  for (const auto& p : pts) {
    const double v[3] = {1, p[0], p[0] * p[0]};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += v[i] * v[j];
      a[i][3] += v[i] * p[1];
    }
  }
  for (int i = 0; i < 3; ++i)
    for (int k = i + 1; k < 3; ++k) {
      const double f = a[k][i] / a[i][i];
      for (int j = i; j < 4; ++j) a[k][j] -= f * a[i][j];
    }
  std::vector<double> c(3);
  for (int i = 2; i >= 0; --i) {
    double s = a[i][3];
    for (int j = i + 1; j < 3; ++j) s -= a[i][j] * c[j];
    c[i] = s / a[i][i];
  }
  return c;
}

// A circular wall of radius rw about (cx, cy), seen from the car's pose: its points with vehicle
// x in [-5, 20] and on `side`, fitted as the detector would.
WallView circle_wall(double cx, double cy, double rw, int side, double px, double py, double yaw) {
  std::vector<std::array<double, 2>> pts;
  for (int i = 0; i < 3600; ++i) {
    const double a = 2 * M_PI * i / 3600, wx = cx + rw * std::cos(a) - px, wy = cy + rw * std::sin(a) - py;
    const double x = std::cos(yaw) * wx + std::sin(yaw) * wy, y = -std::sin(yaw) * wx + std::cos(yaw) * wy;
    if (x >= -5 && x <= 20 && y * side > 0 && std::abs(y) < 25) pts.push_back({x, y});  // the near side only
  }
  WallView w;
  if (pts.size() < 10) return w;
  w.coefficients = fit_quadratic(pts);
  w.x_min = 1e9;
  w.x_max = -1e9;
  for (const auto& p : pts) w.x_min = std::min(w.x_min, p[0]), w.x_max = std::max(w.x_max, p[0]);
  w.valid = true;
  return w;
}

WallLineParams av21_line() {
  WallLineParams p;
  const auto car = av21_vehicle();
  p.max_curvature = std::tan(0.8 * car.max_steer) / car.wheelbase;
  return p;
}

TrackerParams av21_lqr() {
  TrackerParams tp;
  apply_vehicle(tp, av21_vehicle());
  tp.steer_law = SteerLaw::lqr;
  tp.lqr.r_steer = 200;
  return tp;
}

struct LoopResult {
  double min_distance = 1e9, max_distance = 0, max_speed_target = 0;
};

// A left turn about (0, rc): the car starts at the origin heading +x at speed v, a wall on `side`
// at radius rw; the follower drives a kinematic car for `seconds`, wall frames at 20 Hz. Distances
// to the wall are taken after `settle` seconds.
LoopResult drive_circle(double rc, double rw, int side, double v, double seconds, double settle, double lose_from = -1,
                        double lose_to = -1) {
  const auto car = av21_vehicle();
  WallFollowerParams policy;
  policy.reduce_speed = false;  // hold: the speed is the test's
  WallLineFollower f(av21_line(), policy, av21_lqr());
  double x = 0, y = 0, yaw = 0, steer = 0;
  const double dt = 0.01;
  f.engage(0, v);
  LoopResult r;
  for (int k = 0; k * dt < seconds; ++k) {
    const double t = k * dt;
    if (k % 5 == 0) {
      const bool lost = t >= lose_from && t < lose_to;
      const WallView w = lost ? WallView{} : circle_wall(0, rc, rw, side, x, y, yaw);
      f.walls(t, side > 0 ? w : WallView{}, side < 0 ? w : WallView{});
    }
    const double yaw_rate = v * std::tan(steer) / car.wheelbase;
    const Command c = f.control(t, v, yaw_rate);
    r.max_speed_target = std::max(r.max_speed_target, c.target_speed);
    steer = c.steer;
    const double w = v * std::tan(steer) / car.wheelbase;
    x += v * dt * std::cos(yaw + 0.5 * w * dt);
    y += v * dt * std::sin(yaw + 0.5 * w * dt);
    yaw += w * dt;
    f.moved(dt, v, w);
    if (t >= settle) {
      const double d = std::abs(std::hypot(x, y - rc) - rw);
      r.min_distance = std::min(r.min_distance, d);
      r.max_distance = std::max(r.max_distance, d);
    }
  }
  return r;
}

}  // namespace

TEST(WallLine, ChoosesTheNearerWallAndKeepsIt) {
  const WallView left = straight(4), right = straight(-7), none;
  EXPECT_EQ(choose_wall(0, left, right), 1);           // take-over: the nearer
  EXPECT_EQ(choose_wall(0, straight(9), right), -1);
  EXPECT_EQ(choose_wall(-1, left, right), -1);         // followed and valid: kept
  EXPECT_EQ(choose_wall(-1, left, none), 1);           // lost: the other
  EXPECT_EQ(choose_wall(1, none, none), 0);
  EXPECT_EQ(choose_wall(0, straight(-3), right), -1);  // the left detector's fit of the right wall: not a left wall
  EXPECT_EQ(choose_wall(0, straight(25), none), 0);    // across a hairpin: too far to follow
  WallView broken = left;
  broken.coefficients[1] = NAN;
  EXPECT_EQ(choose_wall(0, broken, none), 0);          // a malformed fit is no wall
}

TEST(WallLine, GapIsTheCarsDistanceCutWhereTheWallBendsAway) {
  WallLineParams p;
  p.max_curvature = 0.1;  // the car turns no tighter than 10 m
  EXPECT_DOUBLE_EQ(line_gap(straight(-5), -1, 5, p), 5);
  EXPECT_DOUBLE_EQ(line_gap(straight(-1), -1, 1, p), p.min_gap);
  EXPECT_DOUBLE_EQ(line_gap(straight(-12), -1, 12, p), p.max_gap);
  // A right wall bending left (the outside of a left turn) at radius 15: y = -8 + x^2 / 30.
  const WallView outer{{-8, 0, 1.0 / 30}, true, -5, 20};
  EXPECT_NEAR(line_gap(outer, -1, 8, p), 15 - 10, 1e-9);
  // The same wall on the left, bending away from it (the inside of the turn): no cut.
  const WallView inner{{8, 0, 1.0 / 30}, true, -5, 20};
  EXPECT_DOUBLE_EQ(line_gap(inner, 1, 8, p), 8);
}

TEST(WallLine, OffsetLineKeepsTheGapAndSlowsForItsCurvature) {
  WallLineParams p;
  const auto line = offset_line(straight(-6), -1, 4, 30, p);
  ASSERT_GT(line.size(), 40u);
  EXPECT_DOUBLE_EQ(line.front().x, -p.behind);
  for (const auto& q : line) {
    EXPECT_NEAR(q.y, -2, 1e-12);
    // Past the wall's seen end (x = 20) the line may be the tightest turn the car can take.
    EXPECT_DOUBLE_EQ(q.speed, q.x <= 20 ? 30 : std::sqrt(p.a_lat / p.max_curvature));
  }
  EXPECT_NEAR(line.back().x, 20 + p.extend, 1e-9);
  // The outside of a left turn, radius 30 at x = 0: the line 5 m in has radius 25 there.
  const WallView outer{{-5, 0, 1.0 / 60}, true, -5, 20};
  const auto bend = offset_line(outer, -1, 5, 100, p);
  const auto& at0 = bend[static_cast<std::size_t>(p.behind)];
  EXPECT_NEAR(at0.x, 0, 1e-12);
  EXPECT_NEAR(at0.y, 0, 1e-12);
  EXPECT_NEAR(at0.speed, std::sqrt(p.a_lat * 25), 1e-9);
  for (const auto& q : bend) EXPECT_LE(q.speed, 100);
}

TEST(WallLine, FollowsTheOutsideWallOfATurn) {
  // Radius 60 about the car's turn, wall 6 m to the right: the line is the car's own circle.
  const LoopResult r = drive_circle(60, 66, -1, 20, 20, 2);
  EXPECT_GT(r.min_distance, 5.6);
  EXPECT_LT(r.max_distance, 6.4);
}

TEST(WallLine, FollowsTheInsideWallOfATurn) {
  const LoopResult r = drive_circle(60, 54, 1, 20, 20, 2);
  EXPECT_GT(r.min_distance, 5.6);
  EXPECT_LT(r.max_distance, 6.4);
}

TEST(WallLine, AHairpinsOutsideWallMovesTheLineOutToWhatTheCarCanTurn) {
  // The car on a 10 m circle, the outer wall at 18 m: 8 m in, the line would need a 10 m turn
  // (max_curvature with the margin is about 1/10.6 m), so the gap is cut and the car moves out.
  const WallLineParams p = av21_line();
  const LoopResult r = drive_circle(10, 18, -1, 8, 20, 8);
  EXPECT_GE(r.min_distance, p.min_gap);
  EXPECT_LT(r.max_distance, 18 - 1 / p.max_curvature + 0.5);
  EXPECT_LE(r.max_speed_target, 8 + 1e-9);
}

TEST(WallLine, ALostWallIsHeldThenTheFollowerBrakes) {
  // The wall is gone for 0.6 s (under hold_s): the car keeps to the carried line.
  const LoopResult r = drive_circle(60, 66, -1, 20, 12, 2, 5, 5.6);
  EXPECT_GT(r.min_distance, 5.6);
  EXPECT_LT(r.max_distance, 6.4);
  WallLineFollower f(av21_line(), WallFollowerParams{}, av21_lqr());
  f.engage(0, 20);
  f.walls(0, WallView{}, straight(-6));
  EXPECT_TRUE(f.has_line(0.9));
  EXPECT_EQ(f.control(0.9, 20, 0).brake, 0);
  EXPECT_FALSE(f.has_line(1.1));
  EXPECT_EQ(f.control(1.1, 20, 0).brake, 1);
  f.walls(1.2, straight(5), WallView{});  // a wall again: taken afresh, the other side
  EXPECT_EQ(f.side(), 1);
  EXPECT_DOUBLE_EQ(f.gap(), 5);
  // Handed the car at a standstill (the manager's resume_on_wall): it drives off to restart_speed.
  f.engage(2, 0);
  f.walls(2, WallView{}, straight(-6));
  const Command off = f.control(2.05, 0, 0);
  EXPECT_NEAR(off.target_speed, WallFollowerParams{}.restart_speed, 1e-9);
  EXPECT_GT(off.throttle, 0);
}

// ---- the map's edge laid onto the LiDAR's wall (common/mapped_wall.hpp) ----

namespace {

// A ring of radius 100 m, 6 m to each edge, points every 5 m, driven anticlockwise; the car at
// (100, 0) heading +y: the left edge is the inner circle, the right the outer.
brickyard::track::Track ring() {
  brickyard::track::TrackGeometry g;
  g.line = circle_line<brickyard::track::CenterLine>(100, 126, 6);
  return brickyard::track::Track(g);
}

// A wall fitted to a polyline's points within x in [-5, 20], as the detector would.
WallView seen_polyline(const std::vector<EdgePoint>& edge) {
  std::vector<std::array<double, 2>> pts;
  for (std::size_t i = 0; i + 1 < edge.size(); ++i)
    for (int k = 0; k < 10; ++k) {
      const double u = k / 10.0, x = edge[i].x + u * (edge[i + 1].x - edge[i].x), y = edge[i].y + u * (edge[i + 1].y - edge[i].y);
      if (x >= -5 && x <= 20) pts.push_back({x, y});
    }
  return {fit_quadratic(pts), true, -5, 20};
}

}  // namespace

TEST(MappedWall, TheEdgeRoundTheCarInItsFrame) {
  const auto track = ring();
  int hint = -1;
  const auto left = mapped_edge(track, 1, 100, 0, M_PI / 2, 10, 100, hint);
  const auto right = mapped_edge(track, -1, 100, 0, M_PI / 2, 10, 100, hint);
  ASSERT_GE(left.size(), 20u);
  EXPECT_LE(left.front().x, -10 + 1e-9 + 0.5);  // from at least 10 m behind...
  EXPECT_GE(right.back().x, 50);                 // ...to well ahead, round the bend
  for (const auto& e : left) {
    EXPECT_NEAR(std::hypot(e.x + 0, e.y - 100), 94, 0.1);  // the centre is at (0, 100) in the car's frame
  }
  for (const auto& e : right) EXPECT_NEAR(std::hypot(e.x, e.y - 100), 106, 0.1);
}

TEST(MappedWall, RegistrationFindsTheEstimatesDriftAndRefusesAnotherShape) {
  const auto track = ring();
  int hint = -1;
  const auto edge = mapped_edge(track, -1, 100, 0, M_PI / 2, 10, 100, hint);
  // The truth: the car is 0.8 m farther from the right wall and turned 0.04 rad from what the
  // estimate says, so the LiDAR sees the edge turned and shifted.
  const EdgeRegistration truth{-0.8, 0.04, 0, 0, true};
  const WallView wall = seen_polyline(registered(edge, truth));
  const EdgeRegistration r = register_edge(edge, wall, RegistrationParams{});
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.shift, -0.8, 0.05);
  EXPECT_NEAR(r.turn, 0.04, 0.005);
  EXPECT_LT(r.rms, 0.05);
  // A wall bending the other way (not this edge: the estimate is somewhere else) is refused.
  WallView other = wall;
  other.coefficients[2] = -0.02;
  EXPECT_FALSE(register_edge(edge, other, RegistrationParams{}).ok);
  // Too large a correction is no drift either.
  EXPECT_FALSE(register_edge(edge, seen_polyline(registered(edge, {4.0, 0, 0, 0, true})), RegistrationParams{}).ok);
}

TEST(MappedWall, LineInsideAPolylineWallSlowsForItsBendAndKeepsToWhatTheCarTurns) {
  WallLineParams p;
  p.max_curvature = 0.1;
  p.smooth_half = 0;  // resampled only: the geometry exact
  // A right wall on the outside of a left turn of radius 30 about (0, 30 - 6): car 6 m in.
  std::vector<EdgePoint> wall;
  for (int i = -12; i <= 120; ++i) {
    const double a = i * 0.5 / 30;
    wall.push_back({30 * std::sin(a), 24 - 30 * std::cos(a)});
  }
  const auto line = offset_polyline(wall, -1, 5, 100, p);
  ASSERT_GE(line.size(), 60u);  // every metre of the wall's 66
  for (std::size_t i = 1; i + 1 < line.size(); ++i) EXPECT_NEAR(std::hypot(line[i].x, line[i].y - 24), 25, 0.01);
  for (const auto& q : line) EXPECT_NEAR(q.speed, std::sqrt(p.a_lat * 25), 0.05);
  // Radius 12: 5 m inside it the line would turn at 7 m, tighter than 10 m: the gap shrinks to
  // what keeps the line at 10 m (2 m), and never below min_gap.
  std::vector<EdgePoint> tight;
  for (int i = -12; i <= 60; ++i) {
    const double a = i * 0.5 / 12;
    tight.push_back({12 * std::sin(a), 6 - 12 * std::cos(a)});
  }
  const auto cut = offset_polyline(tight, -1, 5, 100, p);
  for (std::size_t i = 3; i + 3 < cut.size(); ++i) EXPECT_NEAR(std::hypot(cut[i].x, cut[i].y - 6), 12 - p.min_gap, 0.01);  // ends: tapered
  // Averaged over +-5 m, a wiggle of the map's widths (0.2 m every other point) leaves under 5 cm.
  p.smooth_half = 5;
  std::vector<EdgePoint> wiggly;
  for (int i = 0; i < 40; ++i) wiggly.push_back({5.0 * i, -6 + (i % 2 ? 0.2 : 0.0)});
  const auto even = offset_polyline(wiggly, -1, 5, 30, p);
  for (std::size_t i = 10; i + 10 < even.size(); ++i) EXPECT_NEAR(even[i].y, -0.9, 0.05);
}

// Where the wall stands from the map's edge is learnt while localization is good; only the
// registration's departure from it moves the planner's path while the follower drives.
TEST(WallLine, TheWallsOffsetFromTheEdgeIsLearntNotTakenForDrift) {
  WallFollowerParams hold;
  hold.reduce_speed = false;
  WallLineFollower f(av21_line(), hold, av21_lqr());
  auto edge_at = [](double y) {
    std::vector<EdgePoint> e;
    for (double x = -10; x <= 100; x += 5) e.push_back({x, y});
    return e;
  };
  std::vector<PathPoint> path;
  for (double x = -5; x <= 100; x += 2) path.push_back({x, 0.0, 30.0});
  const WallView wall = straight(-8);  // a wall 2 m beyond the right edge at -6
  const auto edge = edge_at(-6), none = std::vector<EdgePoint>{};
  f.engage(0, 30);
  f.walls(0, WallView{}, wall, &none, &edge, &path, 100, true);  // localization good: learnt
  EXPECT_NEAR(f.learnt(-1, 100).shift, -2, 1e-6);
  EXPECT_NEAR(f.learnt(-1, 135).shift, -2, 1e-6);  // a place not learnt: the nearest bin
  // Driving: the estimate is right, so the path stays where it is...
  f.engage(1, 30);
  f.walls(1, WallView{}, wall, &none, &edge, &path, 105, false);
  for (const auto& q : f.line()) EXPECT_NEAR(q.y, 0.0, 1e-6);
  // ...and 0.5 m off (the edge placed 0.5 m too far left): the path moves 0.5 m right, towards
  // where the car truly is from the wall.
  const auto drifted = edge_at(-5.5);
  for (double t = 1.05; t < 3; t += 0.05) f.walls(t, WallView{}, wall, &none, &drifted, &path, 110, false);
  for (const auto& q : f.line()) EXPECT_NEAR(q.y, -0.5, 1e-3);
}

// A wall frame that arrives late is carried from its stamp: the motion after the stamp, a step
// that straddles it cut at it, oldest first. Set at the stamp and carried by what came after, the
// car's place in the line's frame is the one it would have had with the frame on time; only the
// last `keep` steps are kept.
TEST(WallLine, MotionHistoryCarriesALineFromItsStamp) {
  MotionHistory h(64);
  LineOdometry on_time, late;
  const double dt = 0.01;
  for (int k = 1; k <= 40; ++k) {
    const double t = k * dt, v = 30 + 0.1 * k, w = 0.05 * std::sin(0.2 * k);
    h.add(t, dt, v, w);
    if (t > 0.1049) on_time.advance(t - std::max(t - dt, 0.105), v, w);  // the frame stamped 0.105 s, on time
  }
  h.since(0.105, [&](double d, double v, double w) { late.advance(d, v, w); });
  EXPECT_NEAR(late.x(), on_time.x(), 1e-12);
  EXPECT_NEAR(late.y(), on_time.y(), 1e-12);
  EXPECT_NEAR(late.yaw(), on_time.yaw(), 1e-12);
  EXPECT_GT(late.x(), 8.0);  // it moved: 0.295 s at about 32 m/s
  MotionHistory short_memory(3);
  for (int k = 1; k <= 10; ++k) short_memory.add(k * dt, dt, 1.0, 0.0);
  LineOdometry kept;
  short_memory.since(0.0, [&](double d, double v, double w) { kept.advance(d, v, w); });
  EXPECT_NEAR(kept.x(), 0.03, 1e-12);  // the last three steps only
}

// ---- control.wall_follower's take-over and its offset-line run (engagement.hpp, wall_line_run.hpp) ----

TEST(Engagement, WithoutAManagerTheFollowerEngagesAtItsFirstCommand) {
  Engagement e(false);
  EXPECT_TRUE(e.taking_part());
  EXPECT_TRUE(e.before_command());
  EXPECT_FALSE(e.before_command());
  EXPECT_EQ(e.engaged(), 1u);
  EXPECT_FALSE(e.calibrating());
}

TEST(Engagement, WithAManagerAtEachHandoverAndAfreshWhileStandingBy) {
  Engagement e(true);
  EXPECT_FALSE(e.taking_part());
  EXPECT_TRUE(e.before_command());  // standing by: the speed policy starts from every command
  EXPECT_FALSE(e.mode("path_tracker"));
  EXPECT_TRUE(e.calibrating());     // localization good, the follower standing by
  EXPECT_TRUE(e.mode("wall_follower"));
  EXPECT_FALSE(e.mode("wall_follower"));  // still the follower: no new take-over
  EXPECT_TRUE(e.active());
  EXPECT_TRUE(e.taking_part());
  EXPECT_FALSE(e.calibrating());
  EXPECT_FALSE(e.before_command());
  EXPECT_FALSE(e.mode("path_tracker"));
  EXPECT_TRUE(e.mode("wall_follower"));
  EXPECT_EQ(e.engaged(), 2u);
}

namespace {

WallLineRun av21_run() {
  WallFollowerParams law;
  law.max_steer = av21_vehicle().max_steer;
  return WallLineRun(WallLineParams{}, law, 200, 0.8, av21_vehicle());
}

}  // namespace

// The nearer wall, then the other when it is lost, then the line held: what each frame follows,
// stamped with its newest wall, and the counts the summary reports.
TEST(WallLineRun, EachFrameSaysWhichWallItFollows) {
  WallLineRun run = av21_run();
  EXPECT_FALSE(run.frame(0, false).has_value());  // no wall yet
  EXPECT_FALSE(run.moving());
  run.imu(900'000'000, 0, 20);
  EXPECT_TRUE(run.moving());
  run.engage(0.9, 20);
  run.wall(0, straight(5), 5, 1'000'000'000);
  run.wall(1, straight(-7), -7, 950'000'000);
  const auto first = run.frame(1.0, false);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->stamp_ns, 1'000'000'000);
  EXPECT_TRUE(first->valid);
  EXPECT_EQ(first->coefficients, straight(5).coefficients);
  EXPECT_EQ(first->distance, 5);  // the left wall, left positive
  EXPECT_FALSE(run.frame(1.0, false).has_value());  // one frame, one line
  EXPECT_LT(run.control(1.0, 20).brake, 1);  // a line to follow
  run.wall(0, straight(5), NAN, 1'100'000'000);  // a distance that is not finite: no wall
  run.wall(1, straight(-7), -7, 1'100'000'000);
  const auto second = run.frame(1.1, false);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->coefficients, straight(-7).coefficients);
  EXPECT_EQ(second->distance, -7);
  run.wall(0, WallView{}, NAN, 1'200'000'000);
  run.wall(1, WallView{}, NAN, 1'200'000'000);
  const auto held = run.frame(1.2, false);
  ASSERT_TRUE(held.has_value());
  EXPECT_TRUE(held->valid);  // the last line, held
  EXPECT_EQ(held->distance, -7);
  EXPECT_EQ(run.control(2.2, 20).brake, 1);  // held past hold_s: none
  const std::vector<std::pair<std::string, double>> m = run.metrics();
  ASSERT_EQ(m.size(), 8u);
  EXPECT_EQ(m[0], (std::pair<std::string, double>("wall_switches", 1)));
  EXPECT_EQ(m[1], (std::pair<std::string, double>("frames_left", 1)));
  EXPECT_EQ(m[2], (std::pair<std::string, double>("frames_right", 2)));
  EXPECT_EQ(m[3], (std::pair<std::string, double>("frames_held", 1)));
  EXPECT_EQ(m[4].first, "lines_planned");
  EXPECT_EQ(m[5].first, "wall_bins_learnt");
  EXPECT_EQ(m[6], (std::pair<std::string, double>("lines_mapped", 0)));
  EXPECT_EQ(m[7], (std::pair<std::string, double>("lines_polynomial", 2)));
}

// The map's edge is placed with the estimate nearest the frame's stamp (a later one, far off,
// would not lay onto the wall); the same map again is kept, a broken one ignored.
TEST(WallLineRun, TheMapsEdgeIsPlacedWithTheEstimateOfTheFramesStamp) {
  WallLineRun run = av21_run();
  brickyard::track::TrackGeometry g;
  g.line = circle_line<brickyard::track::CenterLine>(100, 126, 6);
  EXPECT_EQ(run.map(g), "");
  EXPECT_EQ(run.map(g), "");
  brickyard::track::TrackGeometry broken;
  broken.line = circle_line<brickyard::track::CenterLine>(100, 3, 6);
  EXPECT_EQ(run.map(broken), "map ignored: track needs at least 4 points with x, y and both widths");
  run.estimate(1'000'000'000, {100, 0, M_PI / 2});
  run.estimate(1'040'000'000, {0, 0, 0});
  int hint = -1;
  const WallView right = seen_polyline(mapped_edge(ring(), -1, 100, 0, M_PI / 2, 10, 250, hint));
  run.engage(1.0, 30);
  run.wall(1, right, right.coefficients[0], 1'010'000'000);
  const auto f = run.frame(1.05, false);
  ASSERT_TRUE(f.has_value());
  EXPECT_TRUE(f->valid);
  const auto m = run.metrics();
  EXPECT_EQ(m[6], (std::pair<std::string, double>("lines_mapped", 1)));
  EXPECT_EQ(m[7], (std::pair<std::string, double>("lines_polynomial", 0)));
}
