// The replay plugin's checks and its queue, framework-free (the recordings themselves are read in
// the graph and evidence tests: tests/graphs/replay).
#include "replay/common/replay_checks.hpp"
#include "replay/common/sample_queue.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace brickyard::replay {
namespace {

TEST(ReplayChecks, ARecordingReplaysOnTheClockItWasMadeOn) {
  EXPECT_EQ(clock_problem("r.mcap", "sim", true, false), "");
  EXPECT_EQ(clock_problem("r.mcap", "real", false, false), "");
  EXPECT_EQ(clock_problem("r.mcap", "real", true, false),
            "recording r.mcap was made on the real clock, this run is on the sim clock: its samples' times would not line up");
  EXPECT_EQ(clock_problem("r.mcap", "", true, false),
            "recording r.mcap was made on the unknown clock, this run is on the sim clock: its samples' times would not line up");
}

TEST(ReplayChecks, RetimingTakesARealClockRecordingOntoTheSimClockOnly) {
  EXPECT_EQ(clock_problem("r.mcap", "real", true, true), "");
  EXPECT_NE(clock_problem("r.mcap", "sim", true, true).find("re-times a real-clock recording onto the sim clock"), std::string::npos);
  EXPECT_NE(clock_problem("r.mcap", "real", false, true).find("this run is on the real clock"), std::string::npos);
}

TEST(ReplayChecks, TypeAndDefinition) {
  RecordedTopic t{1, "estimator.estimate", "brickyard::msgs::LocalizationEstimate", "abc", ""};
  EXPECT_EQ(type_problem("r.mcap", t.name, t, t.type, "abc", "LocalizationEstimate"), "");
  EXPECT_NE(type_problem("r.mcap", t.name, t, "brickyard::msgs::Path", "abc", "Path").find("holds brickyard::msgs::LocalizationEstimate, this node replays Path"),
            std::string::npos);
  EXPECT_NE(type_problem("r.mcap", t.name, t, t.type, "def", "LocalizationEstimate").find("(IDL hash abc, this build def)"),
            std::string::npos);
}

TEST(ReplayChecks, Retimed) {
  EXPECT_EQ(retimed(500, -1), 500);
  EXPECT_EQ(retimed(500, 200), 300);
  EXPECT_EQ(retimed(200, 200), 0);
  EXPECT_FALSE(retimed(199, 200));  // from before the drive: dropped
}

TEST(SampleQueue, LetsEachSampleGoOnceItsTimeIsReached) {
  SampleQueue<int> q;
  for (int i = 0; i < 4; ++i) q.push(i * 10, i);
  std::vector<int> sent;
  q.release(15, [&](int m) { sent.push_back(m); });
  EXPECT_EQ(sent, (std::vector<int>{0, 1}));
  q.release(15, [&](int m) { sent.push_back(m); });  // nothing twice
  EXPECT_EQ(q.sent(), 2u);
  q.release(30, [&](int m) { sent.push_back(m); });
  EXPECT_EQ(sent, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(q.left(), 0u);
  EXPECT_EQ(q.size(), 4u);
}

}  // namespace
}  // namespace brickyard::replay
