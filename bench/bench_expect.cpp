// What testing.expect costs per field it checks (target: at most 2 us per decoded field
// check on a Path of 300 poses), beside a baseline in the same run: the hand-written probe it
// replaces — Fast DDS's generated type decoding the same bytes, and the same checks in C++.
// Each sample: 300 poses, four expectations over every pose (x and y in range, speed in range,
// s increasing): 1200 field checks. Medians of 7 rounds of 200 samples (--quick: 3 of 50).
// Exits 1 when the two disagree: a check failed, or they made different numbers of checks.
// usage: bench_expect [--quick]
#include "testing/expect/expectations.hpp"
#include "record/recorder.hpp"           // idl_text, omgidl_schema
#include "record/sample_serializer.hpp"

#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/PathPubSubTypes.h>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::string type = "brickyard::msgs::Path";
  brickyard::msgs::Path path;
  path.header().frame_id("map");
  for (int i = 0; i < 300; ++i) {
    brickyard::msgs::Pose2D p;
    p.x(0.5 * i), p.y(std::sin(0.01 * i)), p.yaw(0.01 * i);
    path.poses().push_back(p);
    path.speed().push_back(40 + 0.1 * i);
    path.s().push_back(0.5 * i);
    path.curvature().push_back(0.001);
  }
  brickyard::fw::SampleSerializer ser(type);
  const auto b = ser.serialize(&path);
  const std::vector<unsigned char> bytes(b.data, b.data + b.size);

  const brickyard::cdr::CdrJson idl(brickyard::fw::omgidl_schema(brickyard::fw::idl_text(type)));
  const auto spec = nlohmann::json::parse(R"([
    {"field": "poses[*].x", "range": [-1000, 1000]},
    {"field": "poses[*].y", "range": [-1000, 1000]},
    {"field": "speed[*]", "range": [0, 100]},
    {"field": "s[*]", "increasing": true}])");
  const int kSamples = quick ? 50 : 200, kRounds = quick ? 3 : 7;
  std::vector<double> ours, base;
  std::uint64_t checks = 0, failures = 0, disagreements = 0;
  for (int r = 0; r < kRounds; ++r) {
    brickyard::testing::ExpectationChecker c(brickyard::testing::parse_expectations(spec, idl, type, nullptr, ""));
    auto t0 = Clock::now();
    for (int k = 0; k < kSamples; ++k) c.observe(0.05 * k, idl.decode(type, bytes.data(), bytes.size()));
    ours.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    checks = c.field_checks();
    failures += c.finish().size();

    // The probe it replaces: the generated type's decoding, the same four checks.
    brickyard::msgs::PathPubSubType support;
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
    std::uint64_t base_checks = 0, bad = 0;
    t0 = Clock::now();
    for (int k = 0; k < kSamples; ++k) {
      std::memcpy(payload.data, bytes.data(), bytes.size());
      payload.length = static_cast<std::uint32_t>(bytes.size());
      payload.pos = 0;
      brickyard::msgs::Path m;
      support.deserialize(&payload, &m);
      double prev = -1e300;
      for (std::size_t i = 0; i < m.poses().size(); ++i) {
        bad += !(m.poses()[i].x() >= -1000 && m.poses()[i].x() <= 1000);
        bad += !(m.poses()[i].y() >= -1000 && m.poses()[i].y() <= 1000);
        bad += !(m.speed()[i] >= 0 && m.speed()[i] <= 100);
        bad += !(m.s()[i] > prev);
        prev = m.s()[i];
        base_checks += 4;
      }
    }
    base.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    failures += bad;
    if (base_checks != checks) {
      std::fprintf(stderr, "bench_expect: testing.expect made %llu checks, the probe %llu\n", (unsigned long long)checks,
                   (unsigned long long)base_checks);
      ++disagreements;
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double o = median(ours) / static_cast<double>(checks) * 1e6, bl = median(base) / static_cast<double>(checks) * 1e6;
  std::printf("testing.expect on a Path of 300 poses: %llu field checks a round of %d samples, medians of %d rounds\n",
              static_cast<unsigned long long>(checks), kSamples, kRounds);
  std::printf("%-58s %10s %14s\n", "", "us/check", "us/sample");
  std::printf("%-58s %10.3f %14.1f\n", "ours: testing.expect (IDL decoding, paths, checks)", o, o * static_cast<double>(checks) / kSamples);
  std::printf("%-58s %10.3f %14.1f\n", "baseline: a hand-written probe (generated type, C++)", bl, bl * static_cast<double>(checks) / kSamples);
  std::printf("ratio ours/baseline: %.1f; target: at most 2 us a check -> %s\n", o / bl, o <= 2.0 ? "met" : "NOT met");
  if (failures != 0) std::fprintf(stderr, "bench_expect: %llu checks failed on a path that meets every expectation\n", (unsigned long long)failures);
  return failures == 0 && disagreements == 0 ? 0 : 1;
}
