#include "testing/assert_sink/stream_checker.hpp"
#include "testing/scripted_source/script.hpp"

#include <gtest/gtest.h>

using namespace brickyard::testing;

TEST(ScalarScript, RampWithCount) {
  ScalarScript s({}, false, 1.0, 0.5, 3);
  EXPECT_EQ(*s.next(), 1.0);
  EXPECT_EQ(*s.next(), 1.5);
  EXPECT_EQ(*s.next(), 2.0);
  EXPECT_FALSE(s.next());
}

TEST(ScalarScript, ValuesOnceOrLooped) {
  ScalarScript once({4, 5}, false, 0, 1, -1);
  EXPECT_EQ(*once.next(), 4);
  EXPECT_EQ(*once.next(), 5);
  EXPECT_FALSE(once.next());
  ScalarScript looped({4, 5}, true, 0, 1, 5);
  std::vector<double> got;
  while (auto v = looped.next()) got.push_back(*v);
  EXPECT_EQ(got, (std::vector<double>{4, 5, 4, 5, 4}));
}

TEST(StreamChecker, CountsAndRate) {
  StreamExpectations e;
  e.min_count = 3;
  e.min_rate_hz = 9.9;
  e.max_rate_hz = 10.1;
  StreamChecker c(e);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(c.observe(i * 100'000'000LL, i));
  EXPECT_DOUBLE_EQ(c.rate_hz(), 10.0);
  EXPECT_TRUE(c.finish().empty());
  StreamChecker few(e);
  few.observe(0, 1);
  EXPECT_EQ(few.finish().size(), 2u);  // too few, and no rate from one sample
}

TEST(StreamChecker, RateViolation) {
  StreamExpectations e;
  e.max_rate_hz = 5;
  StreamChecker c(e);
  c.observe(0, 0);
  c.observe(100'000'000, 0);
  ASSERT_EQ(c.finish().size(), 1u);
  EXPECT_NE(c.finish()[0].find("above max_rate_hz"), std::string::npos);
}

TEST(StreamChecker, OrderingRangeAndExactValues) {
  StreamExpectations e;
  e.ordering = "increasing";
  e.max_value = 10;
  e.expect_values = {1, 2};
  StreamChecker c(e);
  EXPECT_FALSE(c.observe(0, 1));
  auto v = c.observe(1, 3);
  ASSERT_TRUE(v);
  EXPECT_NE(v->find("expected 2"), std::string::npos);
  EXPECT_NE(c.observe(2, 3)->find("not increasing"), std::string::npos);
  EXPECT_NE(c.observe(3, 11)->find("above max_value"), std::string::npos);
}

TEST(StreamChecker, MaxCount) {
  StreamExpectations e;
  e.max_count = 1;
  StreamChecker c(e);
  EXPECT_FALSE(c.observe(0, 0));
  EXPECT_TRUE(c.observe(1, 0));
}

TEST(StreamChecker, DigestSeesEveryBit) {
  StreamChecker a({}), b({}), c({});
  a.observe(1, 0.5);
  b.observe(1, 0.5);
  c.observe(1, 0.5000000000000001);
  EXPECT_EQ(a.digest(), b.digest());
  EXPECT_NE(a.digest(), c.digest());
}
