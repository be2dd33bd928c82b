// A rival's start checked (issue 46): off the road (sim/common/car_on_track.hpp) and inside our
// car (sim/common/race_judge.hpp), called directly.
#include "sim/common/car_on_track.hpp"
#include "sim/common/race_judge.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

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

// At validation (sim.vehicle's `clear_of`): a start whose footprint overlaps another's, named with
// both places; clear ahead, behind and beside; the short way round the loop's start line.
TEST(RivalStart, AStartInsideAnotherIsNamed) {
  const double front = 3.9, rear = 1.0, half = 0.97, loop = 4000;
  EXPECT_NE(start_inside({2, 0}, {0, 0}, front, rear, half, loop).find("the car at s = 2.0 m, d = 0.00 m stands inside the one starting at s = 0.0 m, d = 0.00 m"),
            std::string::npos);
  EXPECT_NE(start_inside({-4.8, 1.0}, {0, 0}, front, rear, half, loop), "") << "behind, its nose in our tail";
  EXPECT_EQ(start_inside({5.0, 0}, {0, 0}, front, rear, half, loop), "") << "a car's length ahead";
  EXPECT_EQ(start_inside({-5.0, 0}, {0, 0}, front, rear, half, loop), "");
  EXPECT_EQ(start_inside({1, 1.95}, {0, 0}, front, rear, half, loop), "") << "beside, a car's width across";
  EXPECT_NE(start_inside({3998, 0}, {1, 0}, front, rear, half, loop), "") << "across the start line";
  EXPECT_EQ(start_inside({3998, 0}, {1, 0}, front, rear, half, 0), "") << "no loop known: s as given";
}

TEST(RivalStart, StartsAreSAndDPairsNamedByPointer) {
  const auto starts = parse_starts("[[0, 0], [120.5, -1.5]]");
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_EQ(starts[1].s, 120.5);
  EXPECT_EQ(starts[1].d, -1.5);
  EXPECT_TRUE(parse_starts("[]").empty());
  auto message = [](const char* text) {
    try {
      parse_starts(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("[[0]]"), "/0: not an [s, d] pair");
  EXPECT_EQ(message("[[0, 0], [1, \"a\"]]"), "/1/1: not a finite number");
  EXPECT_EQ(message("{}"), "not a JSON array of [s, d] pairs");
}
