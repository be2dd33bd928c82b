// The simulated race control (common/race_control_sim.hpp): its script read and refused, its
// frames (rate, heartbeat, laps, silences) read back by the vehicle interface's reader; and its
// judge (common/flag_judge.hpp) on cars that do and do not do what the flags ask.
#include "sim/common/flag_judge.hpp"
#include "sim/common/race_control_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::sim;
namespace vi = brickyard::vehicle_interface;

namespace {

constexpr int64_t kMs = 1'000'000;

std::vector<FlagEntry> script(const std::string& json) {
  std::string error;
  std::optional<std::vector<FlagEntry>> s = parse_flag_script(json, {}, error);
  EXPECT_TRUE(s) << error;
  return s.value_or(std::vector<FlagEntry>{});
}

std::string refusal(const std::string& json) {
  std::string error;
  EXPECT_FALSE(parse_flag_script(json, {}, error)) << json;
  return error;
}

vi::RaceControlDbc race_dbc() {
  const vi::DbcReadResult read = vi::load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  std::string error;
  return *vi::RaceControlDbc::make(*read.database, "CAN1-INDY-V14.dbc", error);
}

// A car on a straight line at speed v(t) given by `speed`, judged every 10 ms.
template <class Speed> std::vector<JudgeNotice> drive(FlagJudge& j, double from, double to, double& x, Speed speed) {
  std::vector<JudgeNotice> said;
  for (double t = from; t < to - 1e-9; t += 0.01) {
    const double v = speed(t);
    x += v * 0.01;
    for (JudgeNotice& n : j.truth(t, x, 0, v)) said.push_back(std::move(n));
  }
  return said;
}

}  // namespace

TEST(FlagScript, ReadsNamesAndCodesAndNamesWhatIsWrong) {
  const std::vector<FlagEntry> s = script(
      R"([{"t": 0, "track_flag": "green"}, {"t": 8, "track_flag": "yellow", "target_speed_mph": 60},
          {"t": 9, "track_flag": 4, "vehicle_flag": "checkered"}, {"t": 12, "silent": true}])");
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].text, "GREEN (4), NONE (1), 0 mph");
  EXPECT_EQ(s[1].track_code, 3);
  EXPECT_EQ(s[1].target_mph, 60);
  EXPECT_EQ(s[2].vehicle, vi::VehicleFlag::checkered);
  EXPECT_EQ(s[2].vehicle_code, 4);
  EXPECT_TRUE(s[3].silent);
  EXPECT_EQ(refusal("[]"), "a JSON list of flags, at least one");
  EXPECT_EQ(refusal(R"([{"t": 1, "track_flag": "blue"}])"), "/0/track_flag: 'blue' is no flag of this field");
  EXPECT_EQ(refusal(R"([{"t": 2, "track_flag": "red"}, {"t": 1, "track_flag": "red"}])"), "/1/t: a time in s, at or after the entry before's");
  EXPECT_EQ(refusal(R"([{"t": 1, "track_flag": 16}])"), "/0/track_flag: a flag's name or a code 0..15");
  EXPECT_EQ(refusal(R"([{"t": 1, "track_flag": "red", "target_speed_mph": 60.5}])"), "/0/target_speed_mph: a whole number of mph, 0..255");
  EXPECT_EQ(refusal(R"([{"t": 1, "flag": "red"}])"), "/0/flag: no such field (t, track_flag, vehicle_flag, target_speed_mph, silent)");
  EXPECT_EQ(refusal(R"([{"t": 1}])"), "/0/track_flag: missing (or \"silent\": true)");
  EXPECT_EQ(refusal(R"([{"t": 1, "silent": "yes"}])"), "/0/silent: true or false");
}

TEST(SimRaceControl, SendsTheScriptAtItsRateWithItsHeartbeatAndTheLaps) {
  SimRaceControl rc(script(R"([{"t": 0, "track_flag": "green"}, {"t": 0.55, "track_flag": "yellow", "target_speed_mph": 60},
                               {"t": 2.0, "silent": true}])"), 10, 2);
  const vi::RaceControlDbc dbc = race_dbc();
  std::vector<vi::RaceSummary> sent;
  std::vector<std::pair<int64_t, std::string>> began;
  for (int64_t t = 0; t < 3000 * kMs; t += 10 * kMs) {
    rc.station(t < 1000 * kMs ? 2400.0 + 0.06 * (t / kMs) : 5.0);  // the line crossed at 1 s
    const SimRaceControl::Tick tick = rc.step(t);
    if (tick.began) began.emplace_back(t, tick.began->text);
    if (!tick.frame) continue;
    // Each frame as the vehicle interface reads it off the bus.
    const vi::RaceSummaryRead r = dbc.read(dbc.pack(*tick.frame).frame);
    ASSERT_EQ(r.error, "");
    sent.push_back(r.summary);
  }
  ASSERT_EQ(sent.size(), 20u);  // 10 Hz from 0 to 1.9 s, then silent
  for (size_t k = 0; k < sent.size(); ++k) EXPECT_EQ(sent[k].heartbeat, static_cast<int>(k % 16));
  EXPECT_EQ(sent[5].track_code, 4);   // 0.5 s: still green
  EXPECT_EQ(sent[6].track_code, 3);   // 0.6 s: the yellow's first frame
  EXPECT_EQ(sent[6].target_mph, 60);
  EXPECT_EQ(sent[6].rank, 2);
  EXPECT_EQ(sent[9].lap, 0);
  EXPECT_EQ(sent[10].lap, 1);         // 1.0 s: the line crossed
  EXPECT_EQ(sent[9].lap_distance_m, 2454);
  ASSERT_EQ(began.size(), 3u);
  EXPECT_EQ(began[1], std::make_pair(int64_t{600 * kMs}, std::string("YELLOW (3), NONE (1), 60 mph")));
  EXPECT_EQ(began[2], std::make_pair(int64_t{2000 * kMs}, std::string("silent")));
  EXPECT_EQ(rc.laps(), 1);
}

TEST(FlagJudge, AYellowMetWithinItsDistanceAndOneThatIsNot) {
  for (double decel : {6.0, 5.0}) {  // the car brakes at 6 m/s^2, then at 5: the second is too slow
    FlagJudge j({});
    double x = 0;
    drive(j, 0, 1, x, [](double) { return 60.0; });
    FlagEntry yellow;
    yellow.track = vi::TrackFlag::yellow, yellow.target_mph = 60, yellow.text = "YELLOW (3), NONE (1), 60 mph";
    EXPECT_TRUE(j.flag(1.0, yellow).empty());
    const std::vector<JudgeNotice> said = drive(j, 1, 10, x, [&](double t) { return std::max(26.8224, 60.0 - decel * (t - 1.0)); });
    ASSERT_EQ(said.size(), 1u);
    EXPECT_EQ(said[0].fail, decel < 6) << said[0].text;
    // needed (60^2 - 26.8224^2) / 12 = 240.0 m; reached at 27.3224 m/s: (60^2 - 27.3224^2) / 12 = 237.8 m (+ a step);
    // at 5 m/s^2, just past 240.0 m: sqrt(60^2 - 10 x 240.1) = 34.6 m/s
    const std::string want = decel == 6.0 ? "YELLOW at 1.000 s from 60.00 m/s: 26.8 m/s reached after 238.3 m, within the 240.0 m allowed"
                                          : "YELLOW at 1.000 s from 60.00 m/s: still 34.7 m/s after the 240.0 m allowed";
    EXPECT_EQ(said[0].text.substr(0, want.size()), want);
  }
}

TEST(FlagJudge, ARedASilenceAndTheCheckeredLapEachEndInAStop) {
  FlagJudge j({});
  double x = 0;
  drive(j, 0, 1, x, [](double) { return 40.0; });
  FlagEntry red;
  red.track = vi::TrackFlag::red, red.text = "RED (1), NONE (1), 0 mph";
  j.flag(1.0, red);
  std::vector<JudgeNotice> said = drive(j, 1, 10, x, [](double t) { return std::max(0.0, 40.0 - 6.0 * (t - 1.0)); });
  ASSERT_EQ(said.size(), 1u);  // 133.3 m needed, 146.7 allowed
  EXPECT_FALSE(said[0].fail) << said[0].text;
  EXPECT_NEAR(j.last_allowed_m(), 1600.0 / 12 * 1.1, 1e-9);
  // A silence at 30 m/s: the car races on 1 s, then brakes: 30 + 75 m, within 33 + 82.5.
  drive(j, 10, 11, x, [](double) { return 30.0; });
  FlagEntry silent;
  silent.silent = true, silent.text = "silent";
  j.flag(11.0, silent);
  said = drive(j, 11, 20, x, [](double t) { return t < 12 ? 30.0 : std::max(0.0, 30.0 - 6.0 * (t - 12.0)); });
  ASSERT_EQ(said.size(), 1u);
  EXPECT_FALSE(said[0].fail) << said[0].text;
  // The checkered flag: the lap, then a stop from the line; one that never stops fails at the end.
  FlagEntry checkered;
  checkered.track = vi::TrackFlag::green, checkered.vehicle = vi::VehicleFlag::checkered, checkered.text = "GREEN (4), CHECKERED (4), 0 mph";
  drive(j, 20, 21, x, [](double) { return 50.0; });
  EXPECT_TRUE(j.flag(21.0, checkered).empty());
  drive(j, 21, 25, x, [](double) { return 50.0; });
  said = j.lap(25.0, 3);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].text, "checkered at 21.000 s: the lap finished at 25.000 s (lap count 3) at 50.00 m/s");
  said = drive(j, 25, 30, x, [](double) { return 50.0; });  // it does not stop: past 229.2 m it fails
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(said[0].fail);
  EXPECT_EQ(said[0].text, "checkered at 21.000 s: after the line: still 50.0 m/s after the 229.2 m allowed (the car needs 208.3 m at 6 m/s^2)");
  EXPECT_TRUE(j.run_ended(30).empty());
  j.flag(30, red);
  EXPECT_EQ(j.run_ended(31).size(), 1u);  // a red never met
  EXPECT_TRUE(j.run_ended(31).empty());
}
