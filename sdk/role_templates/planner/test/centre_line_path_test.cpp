// The algorithm alone: no SDK, no host, no graph.
#include "../src/centre_line_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace {

// A circle of radius r, counter-clockwise, n points.
my_plugin::CentreLinePath circle(double r, int n) {
  std::vector<double> x, y;
  for (int i = 0; i < n; ++i) {
    x.push_back(r * std::cos(2 * M_PI * i / n));
    y.push_back(r * std::sin(2 * M_PI * i / n));
  }
  return my_plugin::CentreLinePath(x, y);
}

TEST(CentreLinePath, StartsAtTheNearestPointAndReachesAhead) {
  const auto path = circle(100, 360).ahead_of(0, 101, {});  // beside the point at 90 degrees
  ASSERT_GE(path.size(), 2u);
  EXPECT_NEAR(path.front().x, 0, 1e-9);
  EXPECT_NEAR(path.front().y, 100, 1e-9);
  EXPECT_EQ(path.front().s, 0);
  EXPECT_GE(path.back().s, 200);
  EXPECT_LT(path.back().s, 200 + 2);  // one spacing (1.75 m) past the reach at most
  for (std::size_t i = 1; i < path.size(); ++i) EXPECT_GT(path[i].s, path[i - 1].s);
}

TEST(CentreLinePath, CurvatureAndHeadingOfACircle) {
  const auto path = circle(100, 360).ahead_of(100, 0, {});
  EXPECT_NEAR(path[0].curvature, 0.01, 1e-5);  // counter-clockwise: turning left
  EXPECT_NEAR(path[0].yaw, M_PI / 2, 0.01);     // at (100, 0) heading +y
}

TEST(CentreLinePath, SpeedFromTheCurvatureWithinTheTopSpeed) {
  my_plugin::PathSettings s;
  s.a_lat = 9;
  s.v_max = 100;
  const auto tight = circle(100, 360).ahead_of(100, 0, s);
  EXPECT_NEAR(tight[0].speed, 30, 0.01);  // sqrt(9 m/s^2 x 100 m)
  s.v_max = 20;
  EXPECT_EQ(circle(100, 360).ahead_of(100, 0, s)[0].speed, 20);
}

TEST(CentreLinePath, BrakesBeforeATurn) {
  // A straight, then a hairpin: the speed falls towards the turn, never faster than braking allows.
  std::vector<double> x, y;
  for (int i = 0; i <= 100; ++i) x.push_back(i * 5.0), y.push_back(0);
  for (int i = 1; i < 20; ++i) x.push_back(500 + 20 * std::sin(M_PI * i / 20)), y.push_back(20 - 20 * std::cos(M_PI * i / 20));
  for (int i = 100; i >= 0; --i) x.push_back(i * 5.0), y.push_back(40);
  my_plugin::PathSettings s;
  s.ahead_m = 400;
  const auto path = my_plugin::CentreLinePath(x, y).ahead_of(250, 0, s);  // 250 m before the turn
  EXPECT_EQ(path.front().speed, s.v_max);
  for (std::size_t i = 1; i < path.size(); ++i)
    EXPECT_LE(path[i - 1].speed * path[i - 1].speed, path[i].speed * path[i].speed + 2 * s.a_brake * (path[i].s - path[i - 1].s) + 1e-9);
  EXPECT_LT(path[52].speed, 12.7);  // in the hairpin: sqrt(8 m/s^2 x 20 m) = 12.6 m/s
  EXPECT_LT(path[50].speed, 15);  // and braking at its entry
}

TEST(CentreLinePath, RefusesTooFewPoints) {
  EXPECT_THROW(my_plugin::CentreLinePath({0, 1}, {0, 1}), std::invalid_argument);
  EXPECT_THROW(my_plugin::CentreLinePath({0, 1, 2}, {0, 1}), std::invalid_argument);
}

}  // namespace
