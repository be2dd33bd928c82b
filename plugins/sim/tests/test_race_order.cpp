// Who is ahead and the passes (sim/common/race_order.hpp), called directly on a stadium oval.
#include "sim/common/race_order.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::sim;

namespace {

Track oval_track() {
  WorldSpec w;
  for (double s = 0; s < 1000; s += 5) w.line.x.push_back(s), w.line.y.push_back(0);
  for (int i = 0; i < 126; ++i) {
    const double a = -M_PI / 2 + M_PI * i / 126;
    w.line.x.push_back(1000 + 200 * std::cos(a)), w.line.y.push_back(200 + 200 * std::sin(a));
  }
  for (double s = 1000; s > 0; s -= 5) w.line.x.push_back(s), w.line.y.push_back(400);
  for (int i = 0; i < 126; ++i) {
    const double a = M_PI / 2 + M_PI * i / 126;
    w.line.x.push_back(200 * std::cos(a)), w.line.y.push_back(200 + 200 * std::sin(a));
  }
  w.line.width_left.assign(w.line.x.size(), 7.5);
  w.line.width_right.assign(w.line.x.size(), 7.5);
  return Track(w);
}

CarBox at(const Track& t, double s, double d) {
  const Frenet f = t.at(std::fmod(s, t.length()), d);
  const Eigen::Vector2d p = t.position(f);
  return {p.x(), p.y(), t.heading(f), {3.9, 1.0, 0.97}};
}

}  // namespace

// Behind a slower car across the start line: passed once, when we are a car's length past it;
// then it is behind, and it passes us back once we slow; a car running alongside (within a car's
// length either way, on the other side of the road) is never passed back and forth.
TEST(RaceOrder, PassesEachWayAndNoneAlongside) {
  const Track t = oval_track();
  RaceOrder order(t, 4.9);
  const double start = t.length() - 100;  // we start 100 m before the line
  std::vector<RaceOrder::Pass> all;
  for (double time = 0; time < 40; time += 0.01) {
    const double ours = start + (time < 20 ? 60 * time : 1200 + 40 * (time - 20));
    const double slow = start + 40 + 50 * time;
    const double beside = ours + 4 * std::sin(time);
    for (const auto& p : order.update(time, at(t, ours, 2), {at(t, slow, -2), at(t, beside, -4)})) all.push_back(p);
    if (time > 1 && time < 2) EXPECT_EQ(order.position(), 2);
  }
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].car, 0);
  EXPECT_TRUE(all[0].ours);
  EXPECT_NEAR(all[0].t, (40 + 4.9) / 10, 0.02);  // 10 m/s faster: past by a car's length
  EXPECT_FALSE(all[1].ours);
  EXPECT_EQ(order.passes(), 1);
  EXPECT_EQ(order.passed_by(), 1);
  EXPECT_EQ(order.position(), 2);
}
