// Unit tests of the algorithm, framework-free: LowPass is plain C++, so it is tested without the
// SDK, the host or a graph. The graph tests (CMakeLists.txt) check the plugin around it.
#include "../src/filter.hpp"

#include <gtest/gtest.h>

TEST(LowPass, FirstSamplePassesThrough) {
  LowPass f(0.25);
  EXPECT_DOUBLE_EQ(f.update(7.0), 7.0);
}

TEST(LowPass, StepResponseClosesHalfTheGapEachSampleAtAlphaHalf) {
  LowPass f(0.5);
  EXPECT_DOUBLE_EQ(f.update(0.0), 0.0);
  EXPECT_DOUBLE_EQ(f.update(10.0), 5.0);
  EXPECT_DOUBLE_EQ(f.update(10.0), 7.5);
  EXPECT_DOUBLE_EQ(f.update(10.0), 8.75);
}

TEST(LowPass, AlphaOnePassesTheInputThrough) {
  LowPass f(1.0);
  for (double x : {3.0, -2.0, 11.5}) EXPECT_DOUBLE_EQ(f.update(x), x);
}

TEST(LowPass, AlphaZeroHoldsTheFirstSample) {
  LowPass f(0.0);
  f.update(4.0);
  for (double x : {3.0, -2.0, 11.5}) EXPECT_DOUBLE_EQ(f.update(x), 4.0);
}

TEST(LowPass, ConvergesToAConstantInput) {
  LowPass f(0.3);
  f.update(0.0);
  double y = 0;
  for (int i = 0; i < 200; ++i) y = f.update(1.0);
  EXPECT_NEAR(y, 1.0, 1e-12);
}
