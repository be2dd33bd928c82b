// The stop's line with the track's map (common/stop_line.hpp): room to the edges growing with the
// distance covered, the middle where the track is too narrow for it, a path off the map left where
// it is; and in the stop, a heading error at the trip that the path alone takes to the edge.
#include "vehicle_interface/common/path_stop.hpp"
#include "vehicle_interface/common/stop_line.hpp"

#include "av21.hpp"
#include "control/vehicle_tracking.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard;
using namespace brickyard::vehicle_interface;

namespace {

constexpr double kRadius = 300, kHalfWidth = 7.5;

// A ring road turning left about (0, kRadius), its centre line through (0, 0) heading along +x;
// with a wobble, the centre line's radius swings `wobble` m either way `waves` times a lap (a
// chicane's S that a line straight through it cuts).
track::Track ring(double wobble = 0, int waves = 0, double half_width = kHalfWidth, double right_width = kHalfWidth) {
  track::TrackGeometry g;
  g.name = "ring";
  for (int i = 0; i < 1200; ++i) {
    const double a = 2 * M_PI * i / 1200, r = kRadius + wobble * std::sin(waves * a);
    g.line.x.push_back(r * std::sin(a));
    g.line.y.push_back(kRadius - r * std::cos(a));
    g.line.width_left.push_back(half_width);
    g.line.width_right.push_back(wobble == 0 ? right_width : half_width);
  }
  return track::Track(g);
}

// `length` m of the ring at `d` m left of its centre line from `start` m along it, a point each 2 m.
std::vector<control::PathPoint> ring_path(double d, double length, double speed, double start = 0) {
  std::vector<control::PathPoint> pts;
  const double r = kRadius - d;
  for (double s = start; s <= start + length; s += 2) pts.push_back({r * std::sin(s / r), kRadius - r * std::cos(s / r), speed});
  return pts;
}

double left_of_centre(double x, double y) { return kRadius - std::hypot(x, y - kRadius); }

}  // namespace

TEST(StopLine, RoomGrowsWithTheDistanceCoveredUpToTheMiddle) {
  const track::Track track = ring();
  const std::vector<control::PathPoint> path = ring_path(-5, 400, 50);  // 2.5 m from the right edge
  const StopLineParams p;  // 2.5 m at the trip, 1 degree's worth per metre
  const std::size_t from = 10;
  const std::vector<control::PathPoint> line = stop_line(path, from, track, p, {});
  ASSERT_EQ(line.size(), path.size());
  for (std::size_t i = 0; i < from; ++i) {
    EXPECT_EQ(line[i].x, path[i].x);
    EXPECT_EQ(line[i].y, path[i].y);
  }
  for (std::size_t i = from; i < path.size(); ++i) {
    const double along = 2.0 * static_cast<double>(i - from);  // a point each 2 m
    const double grown = along < p.onset_m ? 0.5 * along * along / p.onset_m : along - 0.5 * p.onset_m;
    const double room = std::min(p.edge_room_m + std::tan(M_PI / 180) * grown, kHalfWidth);
    const double d = left_of_centre(line[i].x, line[i].y);
    EXPECT_EQ(line[i].speed, 50);
    if (along > 0.5 * p.smoothing_m && along < 270) {
      EXPECT_NEAR(d, -kHalfWidth + room, 0.05) << along;
    }
    if (along > 300 + p.smoothing_m) {
      EXPECT_NEAR(d, 0, 0.05) << along;  // the middle: the track too narrow for the room
    }
    EXPECT_GE(d + kHalfWidth, std::min(p.edge_room_m, room) - 0.25) << along;  // never nearer the edge than the path
  }
}

// The outside edge nearer than the inside (5 m right, 10 m left), the path crossing the map's
// first point (its start/finish): the room is kept to the right edge all the same.
TEST(StopLine, KeepsRoomToTheNearerEdgeAcrossTheStartLine) {
  const track::Track lopsided = ring(0, 0, 10, 5);
  const std::vector<control::PathPoint> path = ring_path(-2.5, 300, 50, -100);
  const std::vector<control::PathPoint> line = stop_line(path, 0, lopsided, {}, {});
  for (std::size_t i = 50; i + 8 < line.size(); ++i) {  // from 100 m on (past the onset, the start line) to 15 m before the end
    const double grown = 2.0 * static_cast<double>(i) - 30;
    EXPECT_NEAR(left_of_centre(line[i].x, line[i].y), -5 + 2.5 + std::tan(M_PI / 180) * grown, 0.05) << i;
  }
}

TEST(StopLine, KeepsLessRoomWhereThePathHadLessAndLeavesAPathOffTheMap) {
  const track::Track track = ring();
  const std::vector<control::PathPoint> near_edge = ring_path(-6.5, 200, 50);  // 1 m from the edge (an overtake)
  const std::vector<control::PathPoint> line = stop_line(near_edge, 0, track, {}, {});
  EXPECT_NEAR(left_of_centre(line[0].x, line[0].y), -6.5, 0.05);  // no jump at the trip
  EXPECT_NEAR(left_of_centre(line[50].x, line[50].y), -6.5 + std::tan(M_PI / 180) * (100 - 30), 0.05);  // 100 m on
  const std::vector<control::PathPoint> off = ring_path(-9, 200, 50);  // beyond the edge: not the map's to say
  const std::vector<control::PathPoint> same = stop_line(off, 0, track, {}, {});
  for (std::size_t i = 0; i < off.size(); ++i) {
    EXPECT_EQ(same[i].x, off[i].x);
    EXPECT_EQ(same[i].y, off[i].y);
  }
}

// A line straight through a chicane of a narrow track (1.5 m from its edges at the S's peaks): the
// room would squeeze it into the S, tighter than the grip at 50 m/s; the move is kept only at a
// pace that can take it.
TEST(StopLine, MovesOnlyAsFarAsTheLineStaysDrivable) {
  const track::Track chicane = ring(3, 16, 4.5);  // a wave each 118 m, 3 m either way
  const std::vector<control::PathPoint> path = ring_path(0, 300, 50);
  const auto moved_by = [](const std::vector<control::PathPoint>& line, const std::vector<control::PathPoint>& from) {
    double most = 0;
    for (std::size_t i = 0; i < from.size(); ++i) most = std::max(most, std::hypot(line[i].x - from[i].x, line[i].y - from[i].y));
    return most;
  };
  const double slow = moved_by(stop_line(path, 0, chicane, {}, {15, 1, 15}), path);  // (braking gently: 112 m to stand)
  const double fast = moved_by(stop_line(path, 0, chicane, {}, {50, 10, 15}), path);
  EXPECT_GT(slow, 1.0);  // at 15 m/s the S is easy: the line squeezed into it by metres
  EXPECT_LT(fast, 0.3 * slow) << slow;  // at 50 only a quarter of the move, or none
  const std::vector<control::PathPoint> racing = ring_path(-5, 300, 50);
  EXPECT_GT(moved_by(stop_line(racing, 0, ring(), {}, {50, 10, 15}), racing), 2.0);  // a smooth ring at 50: moved
}

// The racing line 2.5 m from the outside edge, the estimate's heading 0.6 degrees off at the trip
// (either way): along the path alone the car ends the 150 m stop 1.5 m nearer the outside edge
// (toward the wall); with the map it is never nearer than 2.2 m.
TEST(StopLine, TheStopKeepsRoomForAHeadingItCannotSee) {
  control::TrackerParams t;
  t.steer_law = control::SteerLaw::lqr;
  t.lqr.r_steer = 200;
  t.command_latency = 0.01;
  control::apply_vehicle(t, av21_vehicle());
  const double v0 = 55, r = kRadius + 5;
  const std::vector<control::PathPoint> path = ring_path(-5, 500, v0);
  for (double error_deg : {0.6, -0.6}) {
    double least_room[2] = {1e9, 1e9};
    for (bool with_map : {false, true}) {
      PathStop stop(t, {});
      if (with_map) stop.map(ring());
      stop.path(0, path);
      stop.estimate({0, -5, error_deg * M_PI / 180, v0, v0 / r, 0, 0});
      ASSERT_TRUE(stop.begin(0));
      // The car itself: on the path, in the single-track model's steady turn for the wheel the stop
      // commands, its rear axle sliding out as the model's does (the stop's dynamics are tested in
      // test_path_stop.cpp).
      const control::LateralModel& m = t.car;
      double x = 0, y = -5, yaw = 0, v = v0, delta = 0;
      for (int k = 1; v > 1 && k <= 20000; ++k) {
        const double now = k * 1e-3;
        const StopCommand c = stop.step(now, v, delta, 6);
        delta = c.steer;
        const double yaw_rate = steady_yaw_rate(t.car, delta, v);
        stop.gyro(now, yaw_rate);
        const double slide = -m.mass * m.lf / ((m.lf + m.lr) * m.cornering_rear) * v * v * yaw_rate;  // the rear axle's, outward
        const double mid = yaw + 0.5e-3 * yaw_rate;
        x += 1e-3 * (v * std::cos(mid) - slide * std::sin(mid)), y += 1e-3 * (v * std::sin(mid) + slide * std::cos(mid));
        yaw += 1e-3 * yaw_rate;
        v -= 1e-3 * c.decel;
        least_room[with_map] = std::min(least_room[with_map], kHalfWidth - std::abs(left_of_centre(x, y)));
      }
      EXPECT_LE(v, 1) << "did not stop";
    }
    // The path's room at the trip, less what the room's onset leaves to the drift (0.2 m at 36 m)
    // and the tracker's settling.
    EXPECT_GT(least_room[true], 2.2) << error_deg;
    if (error_deg > 0) {
      EXPECT_LT(least_room[false], 1.2) << "the case is no test: the path alone kept its room";  // 0.98 m
    }
  }
}
