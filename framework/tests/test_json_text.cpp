// The live scene's JSON text writer (framework/live/json_text.hpp): what it writes parses as the
// JSON it means (nlohmann reads it back), numbers and all.
#include "live/json_text.hpp"

#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using brickyard::fw::JsonText;

// Nested objects and arrays, keys and strings that need escaping, and the commas between.
TEST(JsonText, WritesWhatNlohmannReadsBack) {
  JsonText items;
  items.open('{').key("a").uint(1).close('}');
  items.open('{').key("b").boolean(true).close('}');
  JsonText w;
  w.open('{').key("say \"hi\"\\").str("tab\there\nline\x01").key("empty").open('[').close(']').key("items").open('[').raw(items.text()).close(']');
  w.key("nested").open('{').key("x").num(1.5).key("y").open('[').num(-2.0).num(3.25).close(']').close('}').close('}');
  const auto j = nlohmann::json::parse(w.text());
  EXPECT_EQ(j["say \"hi\"\\"], "tab\there\nline\x01");
  EXPECT_TRUE(j["empty"].is_array() && j["empty"].empty());
  EXPECT_EQ(j["items"][0]["a"], 1);
  EXPECT_EQ(j["items"][1]["b"], true);
  EXPECT_EQ(j["nested"]["x"], 1.5);
  EXPECT_EQ(j["nested"]["y"][1], 3.25);
}

// Shortest numbers read back as the same double; fixed digits are the value rounded to them
// (the integer path for 0 to 6 digits, to_chars beyond); no NaN or infinity: 0.
TEST(JsonText, NumbersReadBackAsWritten) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const double v = u(rng) * std::pow(10.0, static_cast<int>(rng() % 18) - 6);
    JsonText w;
    w.open('[').num(v).num(v, 3).num(v, 0).num(v, 6).close(']');
    const auto j = nlohmann::json::parse(w.text());
    EXPECT_EQ(j[0].get<double>(), v) << w.text();
    for (const auto& [at, digits] : {std::pair{1, 3}, {2, 0}, {3, 6}}) {
      const double scale = std::pow(10.0, digits), got = j[at].get<double>();
      EXPECT_NEAR(got, v, 0.5 / scale * (1 + 1e-9) + std::fabs(v) * 1e-15) << w.text();
      EXPECT_NEAR(got * scale, std::round(got * scale), 1e-6 * std::max(1.0, std::fabs(got * scale))) << w.text();
    }
  }
  JsonText w;
  w.open('[').num(0.0005, 3).num(-0.0004, 3).num(-1.25, 1).num(12.0, 0).num(std::nan(""), 3).num(std::numeric_limits<double>::infinity()).close(']');
  EXPECT_EQ(w.text(), "[0.001,0.000,-1.3,12,0.000,0]");
}
