// testing.expect's parts: field paths checked against a type's IDL, and the checker
// fed decoded samples directly.
#include "cdr/cdr_json.hpp"
#include "cdr/field_path.hpp"
#include "testing/expect/expectations.hpp"
#include "record/recorder.hpp"  // idl_text, omgidl_schema: the IDL texts the build carries

#include <gtest/gtest.h>

using brickyard::cdr::CdrJson;
using brickyard::cdr::FieldPath;
using brickyard::cdr::parse_field_path;
using namespace brickyard::testing;
using nlohmann::json;

namespace {

const std::string kPath = "brickyard::msgs::Path";

const CdrJson& path_idl() {
  static const CdrJson idl(brickyard::fw::omgidl_schema(brickyard::fw::idl_text(kPath)));
  return idl;
}

std::string path_error(const std::string& text) {
  try {
    path_idl().field_kind(kPath, parse_field_path(text));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

// A Path as CdrJson decodes it: n poses along x, speeds 10, 11, ...
json path_sample(int n, std::int64_t stamp_ns = 0) {
  json j = {{"header", {{"stamp_ns", stamp_ns}, {"seq", 0}, {"frame_id", "map"}}}, {"poses", json::array()},
            {"curvature", json::array()}, {"speed", json::array()}, {"s", json::array()}};
  for (int i = 0; i < n; ++i) {
    j["poses"].push_back({{"x", 1.0 * i}, {"y", 0.0}, {"yaw", 0.0}});
    j["speed"].push_back(10.0 + i);
    j["s"].push_back(1.0 * i);
    j["curvature"].push_back(0.0);
  }
  return j;
}

std::vector<Expectation> parse(const std::string& text, bool with_ref = false) {
  return parse_expectations(json::parse(text), path_idl(), kPath, with_ref ? &path_idl() : nullptr, kPath);
}

std::string parse_error(const std::string& text, bool with_ref = false) {
  try {
    parse(text, with_ref);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(FieldPath, PathsAreCheckedAgainstTheType) {
  EXPECT_EQ(path_idl().field_kind(kPath, parse_field_path("poses[*].x")), "number");
  EXPECT_EQ(path_idl().field_kind(kPath, parse_field_path("header.frame_id")), "string");
  EXPECT_EQ(path_idl().field_kind(kPath, parse_field_path("poses")), "sequence");
  EXPECT_EQ(path_idl().field_kind(kPath, parse_field_path("poses[2]")), "struct");
  EXPECT_EQ(path_error("poses[*].q"), "poses[*].q: no member 'q' in Pose2D (members: x, y, yaw)");
  EXPECT_EQ(path_error("posez"), "posez: no member 'posez' in Path (members: header, poses, curvature, speed, s)");
  EXPECT_EQ(path_error("header[0]"), "header[0]: 'header' is not a sequence or an array; it takes no index");
  EXPECT_EQ(path_error("speed.x"), "speed.x: 'speed' has no members");
  EXPECT_THROW(parse_field_path("poses[x]"), std::invalid_argument);
  EXPECT_THROW(parse_field_path("poses..x"), std::invalid_argument);
  EXPECT_THROW(parse_field_path("poses."), std::invalid_argument);
  EXPECT_THROW(parse_field_path(std::string(300, 'a')), std::invalid_argument);
}

TEST(FieldPath, ValuesAreFoundAndMissingOnesNamed) {
  const json j = path_sample(3);
  std::vector<brickyard::cdr::FieldValue> v;
  std::string missing;
  brickyard::cdr::field_values(j, parse_field_path("poses[*].x"), v, missing);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(*v[2].value, 2.0);
  EXPECT_EQ(brickyard::cdr::concrete(parse_field_path("poses[*].x"), v[2].every), "poses[2].x");
  v.clear();
  brickyard::cdr::field_values(j, parse_field_path("poses[5].x"), v, missing);
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(missing, "poses[5].x");
}

TEST(Expect, BadExpectationsAreNamedByTheirPointer) {
  EXPECT_EQ(parse_error("[]"), ": no expectation (a check that checks nothing cannot fail)");
  EXPECT_EQ(parse_error(R"([{"field": "poses[*].q", "range": [0, 1]}])"), "/0/field: poses[*].q: no member 'q' in Pose2D (members: x, y, yaw)");
  EXPECT_EQ(parse_error(R"([{"count": [1, 2]}, {"field": "header.frame_id", "range": [0, 1]}])"),
            "/1/range: header.frame_id is a string, not a number");
  EXPECT_EQ(parse_error(R"([{"field": "speed[0]", "range": [2, 1]}])"), "/0/range: expected finite low <= high, found [2,1]");
  EXPECT_EQ(parse_error(R"([{"field": "speed[0]"}])"),
            "/0: needs exactly one of range, equals, values, increasing, nondecreasing, decreasing, nonincreasing, near, away_from");
  EXPECT_EQ(parse_error(R"([{"field": "speed[0]", "equals": "fast"}])"), "/0/equals: speed[0] is a number; found \"fast\"");
  EXPECT_EQ(parse_error(R"([{"field": "poses[0].x", "near": {"field": "poses[0].x", "within": 1}}])"),
            "/0/near: compares with the input 'ref', which is not wired");
  EXPECT_EQ(parse_error(R"([{"field": "poses[*].x", "near": {"field": "poses[0].x", "within": 1}}])", true),
            "/0/near: poses[*].x: one value each, no [*]");
  EXPECT_NE(parse_error(R"([{"field": "speed[0]", "range": [0, 1], "sometimes": true}])").find("/0/sometimes: unknown"), std::string::npos);
}

TEST(Expect, EveryFailedExpectationIsReportedWithItsSampleAndTime) {
  ExpectationChecker c(parse(R"([
    {"count": [1, 2]},
    {"field": "speed[*]", "range": [10, 12]},
    {"field": "header.stamp_ns", "increasing": true},
    {"field": "s[*]", "increasing": true},
    {"field": "poses[4].x", "equals": 4, "eventually": [0.5, 2]},
    {"field": "header.frame_id", "equals": "map", "always": [0, 10]},
    {"field": "speed[0]", "range": [0, 100], "always": [50, 60]}
  ])"));
  c.observe(0.0, path_sample(3, 100));
  c.observe(1.0, path_sample(5, 200));
  c.observe(2.0, path_sample(4, 200));
  const auto f = c.finish();
  ASSERT_EQ(f.size(), 4u);  // /3 and /5 held, /4 held at 1 s
  EXPECT_EQ(f[0], "/0 count within [1, 2]: 3 samples");
  EXPECT_EQ(f[1], "/1 speed[*] within [10, 12], always in the whole run: sample 1 at 1.000 s: speed[3] = 13 (2 of 3 samples failed)");
  EXPECT_EQ(f[2], "/2 header.stamp_ns sample to sample increasing, always in the whole run: sample 2 at 2.000 s: header.stamp_ns = 200 after 200");
  EXPECT_EQ(f[3], "/6 speed[0] within [0, 100], always in [50 s, 60 s]: no sample in [50 s, 60 s]");
  EXPECT_EQ(c.samples(), 3u);
  EXPECT_GT(c.field_checks(), 20u);
}

// ---- testing.json_source: JSON encoded by the IDL, read back by Fast DDS's own type ----

#include "testing/json_source/json_samples.hpp"

#include <brickyard/msgs/PathPubSubTypes.h>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>

TEST(JsonSource, AMessageFromJsonIsWhatFastDdsReads) {
  const json msg = {{"header", {{"stamp_ns", 123}, {"frame_id", "map"}}},
                    {"poses", {{{"x", 1.5}, {"y", -2}, {"yaw", 0.25}}, {{"x", 3}}}},
                    {"speed", {10, 20.5}}};
  const auto bytes = path_idl().encode(kPath, msg);
  brickyard::msgs::PathPubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<std::uint32_t>(bytes.size());
  brickyard::msgs::Path p;
  ASSERT_TRUE(support.deserialize(&payload, &p));
  EXPECT_EQ(p.header().stamp_ns(), 123);
  EXPECT_EQ(p.header().frame_id(), "map");
  ASSERT_EQ(p.poses().size(), 2u);
  EXPECT_EQ(p.poses()[0].y(), -2);
  EXPECT_EQ(p.poses()[1].x(), 3);
  EXPECT_EQ(p.poses()[1].yaw(), 0);  // left out: zero
  EXPECT_EQ(p.speed(), (std::vector<double>{10, 20.5}));
  EXPECT_TRUE(p.s().empty());
  // And the IDL decoder reads back what was written.
  EXPECT_EQ(path_idl().decode(kPath, bytes.data(), bytes.size())["poses"][0]["yaw"], 0.25);
}

TEST(JsonSource, BadSamplesAreNamedByTheirPointer) {
  auto error = [](const std::string& text) {
    try {
      encode_script(json::parse(text), path_idl(), kPath);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(R"([{"t": 0, "msg": {"poses": [{"x": "a"}]}}])"), "/0/msg/poses/0/x: expected a number, found \"a\"");
  EXPECT_EQ(error(R"([{"t": 0, "msg": {}}, {"t": 1, "msg": {"posez": []}}])"),
            "/1/msg/posez: no member 'posez' in Path (members: header, poses, curvature, speed, s)");
  EXPECT_EQ(error(R"([{"t": 1, "msg": {}}, {"t": 0.5, "msg": {}}])"), "/1/t: 0.5 s is before the sample above it");
  EXPECT_EQ(error(R"([{"t": 0, "msg": {"header": {"seq": -1}}}])"), "/0/msg/header/seq: out of uint32's range, found -1");
  EXPECT_EQ(error(R"([{"t": 0}])"), "/0: expected {\"t\": SECONDS, \"msg\": {...}}");
  EXPECT_EQ(error("[]"), ": expected a list of samples, [{\"t\": S, \"msg\": {...}}, ...]");
  // A message with a header and no stamp is stamped with its time.
  const auto s = encode_script(json::parse(R"([{"t": 0.25, "msg": {}}])"), path_idl(), kPath);
  EXPECT_EQ(path_idl().decode(kPath, s[0].cdr.data(), s[0].cdr.size())["header"]["stamp_ns"], 250000000);
}

TEST(Expect, ValuesOrderAndAge) {
  const std::string scalar = "brickyard::msgs::Scalar";
  const CdrJson idl(brickyard::fw::omgidl_schema(brickyard::fw::idl_text(scalar)));
  auto sample = [](double v, double stamp_s) { return json{{"header", {{"stamp_ns", std::llround(stamp_s * 1e9)}}}, {"value", v}}; };
  ExpectationChecker c(parse_expectations(json::parse(R"([
    {"field": "value", "values": [1, 3, 5]},
    {"field": "value", "decreasing": true},
    {"age_s": [0.1, 0.1]},
    {"field": "value", "values": [1, 3, 5, 7, 9]}
  ])"), idl, scalar, nullptr, ""));
  c.observe(0.1, sample(1, 0.0));
  c.observe(0.2, sample(3, 0.1));
  c.observe(0.35, sample(4, 0.2));
  const auto f = c.finish();
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0], "/0 value of the first 3 samples [1,3,5], always in the whole run: sample 2 at 0.350 s: value = 4, expected 5");
  EXPECT_EQ(f[1], "/1 value sample to sample decreasing, always in the whole run: sample 1 at 0.200 s: value = 3 after 1 (2 of 3 samples failed)");
  EXPECT_EQ(f[2], "/2 age (arrival less header.stamp_ns) within [0.1, 0.1] s: sample 2 at 0.350000 s stamped 0.200000 s: 0.150000 s old");
  EXPECT_EQ(f[3], "/3 value of the first 5 samples [1,3,5,7,9], always in the whole run: sample 2 at 0.350 s: value = 4, expected 5");
  EXPECT_EQ(parse_error(R"([{"age_s": [0, 1]}])").find("/0/age_s"), std::string::npos);  // Path has a header: accepted
  EXPECT_EQ(parse_error(R"([{"field": "speed[*]", "values": [1]}])"), "/0/values: speed[*]: one value a sample, no [*]");
}

TEST(Expect, AwayFromAPointAlongEveryPose) {
  // Poses along x at 0, 1, 2, ...: the 4th (x = 3) is 0.5 from (3, 0.5); an obstacle at (30, 5)
  // stays 5 from them all.
  ExpectationChecker c(parse(R"([
    {"field": ["poses[*].x", "poses[*].y"], "away_from": {"point": [3, 0.5], "beyond": 1}},
    {"field": ["poses[*].x", "poses[*].y"], "away_from": {"point": [30, 5], "beyond": 4.9}},
    {"field": ["poses[2].x", "poses[2].y"], "away_from": {"point": [2, 0], "beyond": 0}}
  ])"));
  c.observe(0.1, path_sample(10));
  const auto f = c.finish();
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0], "/0 (poses[*].x, poses[*].y) at least 1 from (3, 0.5), always in the whole run: sample 0 at 0.100 s: "
                  "poses[3].x = 3, poses[3].y = 0: 0.5 from it");
  EXPECT_EQ(c.field_checks(), 15u);  // 4 to the first failure, 10, 1
  EXPECT_EQ(parse_error(R"([{"field": ["poses[*].x", "poses[*].y"], "away_from": {"point": [1], "beyond": 1}}])"),
            "/0/away_from/point: 1 coordinates against 2 fields");
  EXPECT_EQ(parse_error(R"([{"field": ["poses[*].x", "poses[0].y"], "away_from": {"point": [1, 2], "beyond": 1}}])"),
            "/0/field: poses[0].y: every field with [*], or none");
  EXPECT_EQ(parse_error(R"([{"field": ["poses[*].x", "poses[*].y"], "away_from": {"point": [1, "a"], "beyond": 1}}])"),
            "/0/away_from/point/1: expected a finite number, found \"a\"");
  EXPECT_EQ(parse_error(R"([{"field": ["header.frame_id"], "away_from": {"point": [1], "beyond": 1}}])"),
            "/0/away_from: header.frame_id is a string, not a number");
  EXPECT_EQ(parse_error(R"([{"field": ["poses[*].x"], "away_from": {"point": [1], "beyond": -1}}])"),
            "/0/away_from: expected {\"point\": [X, ...], \"beyond\": DISTANCE >= 0}");
}
