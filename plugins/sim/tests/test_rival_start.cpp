// A rival's start checked (issue 46): off the road (sim/common/car_on_track.hpp) and inside our
// car (sim/common/race_judge.hpp), called directly.
#include "sim/common/car_on_track.hpp"
#include "sim/common/race_judge.hpp"

#include <gtest/gtest.h>

using namespace brickyard::sim;

namespace {

Track straight_track() {
  WorldSpec w;
  for (double s = 0; s <= 2000; s += 5) w.line.x.push_back(s), w.line.y.push_back(0);
  for (double s = 2000; s > 0; s -= 5) w.line.x.push_back(s), w.line.y.push_back(300);  // a long thin loop
  w.line.width_left.assign(w.line.x.size(), 7.5);
  w.line.width_right.assign(w.line.x.size(), 6.0);
  return Track(w);
}

}  // namespace

// A car of 1.94 m whose side would stand beyond an edge is off the road, named with the road's span.
TEST(RivalStart, OffTheRoadIsNamed) {
  const Track t = straight_track();
  EXPECT_EQ(off_the_road(t, 100, 0, 0.97), "");
  EXPECT_EQ(off_the_road(t, 100, 6.5, 0.97), "");
  EXPECT_NE(off_the_road(t, 100, 6.6, 0.97).find("stands off the road at s = 100.0 m, which spans d = -6.00 to 7.50 m"), std::string::npos);
  EXPECT_NE(off_the_road(t, 100, -5.1, 0.97), "");
}

// A car first seen overlapping ours fails the run as a wrong start, named; one first seen clear
// and then hit is a contact.
TEST(RivalStart, ACarStartingInsideOursIsAWrongStart) {
  const Track t = straight_track();
  const Footprint fp{3.9, 1.0, 0.97};
  RaceJudge judge(t, fp, RaceRules{});
  judge.update({0.0, 100, 0, 0, 0});
  auto said = judge.other_cars({CarBox{102, 0.5, 0, fp}});
  ASSERT_FALSE(said.empty());
  EXPECT_EQ(said.back().kind, RefereeNotice::Kind::fail);
  EXPECT_NE(said.back().text.find("car 0 starts inside ours"), std::string::npos);

  RaceJudge clear(t, fp, RaceRules{});
  clear.update({0.0, 100, 0, 0, 0});
  EXPECT_TRUE(clear.other_cars({CarBox{120, 0, 0, fp}}).empty());
  clear.update({0.1, 117, 0, 0, 60});
  said = clear.other_cars({CarBox{120, 0, 0, fp}});
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said.back().text.find("crash: contact with car 0"), std::string::npos);
}
