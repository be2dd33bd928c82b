// Following a moving car (planning/common/follow.hpp), called directly on a straight path.
#include "planning/common/follow.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::planning;

namespace {

// A straight path along x from 0, a point every 2 m, 400 m.
std::vector<PathSample> straight() {
  std::vector<PathSample> p;
  for (double x = 0; x <= 400; x += 2) p.push_back({x, 0, x, 0, 0});
  return p;
}

MovingCar car_at(double x, double y, double speed) { return {x, y, speed, 0, 0.2, 4.9, 1.94}; }

}  // namespace

// Far behind a slower car the cap lets us close at the braking allowed; at the wanted gap (10 m +
// 1 s of its speed) it is its speed; nearer, slower than it, to open the gap again. A car beside
// the path (not in its way), one behind us, a pylon's young track (its speed a guess) and one too
// short for a car are not followed.
TEST(Follow, TheCapClosesTheGapAndHoldsIt) {
  const FollowParams p;
  const auto path = straight();
  const double front = 3.9, half = 0.97;
  double gap = 0;
  // Its centre at 100 + 2.45: its back 100 m ahead of base_link, 96.1 m from our bumper.
  const double far = follow_speed(path, 0, 0, 50, front, half, {car_at(102.45, 0.5, 40)}, p, &gap);
  EXPECT_NEAR(gap, 96.1, 1.0);
  EXPECT_NEAR(far, std::sqrt(40 * 40 + 2 * p.decel * (gap - (p.min_gap + 40 * p.headway_s))), 1e-9);
  const double wanted = p.min_gap + 40 * p.headway_s;
  EXPECT_NEAR(follow_speed(path, 0, 0, 50, front, half, {car_at(front + wanted + 2.45 + 0.001, 0, 40)}, p), 40.0, 0.05);
  EXPECT_LT(follow_speed(path, 0, 0, 50, front, half, {car_at(front + wanted / 2 + 2.45, 0, 40)}, p), 40.0 * 0.6);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(follow_speed(path, 0, 0, 50, front, half, {car_at(60, 5.5, 40)}, p), inf) << "beside the path";
  EXPECT_EQ(follow_speed(path, 0, 0, 50, front, half, {car_at(-30, 0, 40)}, p), inf) << "behind us";
  MovingCar young = car_at(60, 0, 4.0);
  young.speed_sigma = 2.0;
  EXPECT_EQ(follow_speed(path, 0, 0, 50, front, half, {young}, p), inf) << "a young track's speed";
  MovingCar pylon = car_at(60, 0, 20);
  pylon.length = 0.5;
  EXPECT_EQ(follow_speed(path, 0, 0, 50, front, half, {pylon}, p), inf) << "not a car";
  // Two in the way: the nearer one's cap.
  EXPECT_NEAR(follow_speed(path, 0, 0, 50, front, half, {car_at(300, 0, 10), car_at(front + wanted + 2.45 + 0.001, 0, 40)}, p), 40.0, 0.05);
}

// A moving car's detections are left to it; a pylon's, and a car's that stands, are obstacles.
TEST(Follow, AMovingCarsDetectionsAreNotObstacles) {
  const FollowParams p;
  const StampedPose at{0, 10, 0, M_PI / 2, 0, 0};  // at (10, 0) heading +y
  const std::vector<Detection> seen = {{50, 0, 0.3, 1.8}, {30, 2, 0.5, 0.5}};  // (10, 50) and (8, 30) in the map
  const auto kept = not_moving_cars(at, seen, {car_at(10, 52, 40), car_at(8, 31, 0)}, p);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].x, 30);
}

// A car 4 m to the side of the path now, on the racing line's left, where the path crosses over
// to that side further on (before we would reach it): in the way, followed. The same car where
// the path stays away from it is not.
TEST(Follow, ACarWhereThePathGoesIsInItsWay) {
  const FollowParams p;
  std::vector<PathSample> crossing, away;
  for (double x = 0; x <= 400; x += 2) {
    const double d = std::clamp((x - 40) / 100, 0.0, 1.0) * 4;  // over to +4 m between 40 and 140 m
    crossing.push_back({x, d, x, d, 0});
    away.push_back({x, 0, x, 0, 0});
  }
  const MovingCar car = car_at(30, 4, 40);
  EXPECT_LT(follow_speed(crossing, 0, 0, 50, 3.9, 0.97, {car}, p), 40.0);
  EXPECT_EQ(follow_speed(away, 0, 0, 50, 3.9, 0.97, {car}, p), std::numeric_limits<double>::infinity());
}
