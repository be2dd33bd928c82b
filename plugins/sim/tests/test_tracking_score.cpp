// The tracker's score against the truth (sim/common/tracking_score.hpp), called directly.
#include "sim/common/tracking_score.hpp"

#include <gtest/gtest.h>

using namespace brickyard::sim;

// A car 50 m ahead of ours at 50 m/s, both along x: a track 0.2 m off its centre (base_link +
// 1.45 m) at 50.3 m/s is scored in the 30-60 m band; a fast track far from it is a phantom, a
// standing one (a pylon) is not; a frame with no track near it is a miss.
TEST(TrackingScore, ErrorsByBandMissesAndPhantoms) {
  TrackingScore score({}, 2);
  for (double t = 0; t <= 1.0001; t += 0.01) {
    score.ours({t, 50 * t, 0, 0, 50});
    score.other(0, {t, 50 + 50 * t, 0, 0, 50});
  }
  // Between truth samples: the car's centre at t = 0.505 is at 50 + 25.25 + 1.45.
  ASSERT_TRUE(score.frame(0.505, {{76.7 + 0.2, 0, 50.3}, {20, 9, 40}, {30, -5, 0}}));
  ASSERT_TRUE(score.frame(0.6, {}));
  EXPECT_FALSE(score.frame(2.0, {}));  // past the truth: not scored
  const auto& bands = score.bands();
  ASSERT_EQ(bands.size(), 3u);
  EXPECT_EQ(bands[1].name(), "30_60");
  ASSERT_EQ(bands[1].position_errors.size(), 1u);
  EXPECT_NEAR(bands[1].position_errors[0], 0.2, 1e-9);
  EXPECT_NEAR(bands[1].speed_errors[0], 0.3, 1e-9);
  EXPECT_EQ(bands[1].missed, 1u);
  EXPECT_EQ(bands[0].missed + bands[2].missed, 0u);
  EXPECT_EQ(score.phantoms(), 1u);
  EXPECT_EQ(score.frames(), 2u);
}
