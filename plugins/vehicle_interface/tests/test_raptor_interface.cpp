// The car's side of the drive-by-wire stepped as the plugin steps it (every 2 ms), with frames in
// and out as on the bus: each command at its rate with its counter, the watchdog's stop and
// handover seen in the frames themselves, reports read and their problems counted, the gear.
#include "vehicle_interface/common/raptor_interface.hpp"

#include "av21.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>

using namespace brickyard::vehicle_interface;
using brickyard::motion::Command;

namespace {

VehicleCanMapping av21_mapping() {
  static const DbcReadResult read = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(*read.database, "CAN1-INDY-V14.dbc", error);
  std::optional<DbwMaps> maps = dbw_maps(av21_vehicle(), "av21.json", error);
  return VehicleCanMapping(std::move(*dbc), std::move(*maps));
}

constexpr int64_t kMs = 1'000'000;

// Frames sent, by id, in order.
using Sent = std::map<uint32_t, std::vector<CanFrame>>;

// A drive-by-wire that reports a car at `speed` m/s in `gear`: the reports' frames.
std::vector<CanFrame> reports(const VehicleCanMapping& map, double speed, int gear, uint32_t counter) {
  DbwReports r;
  r.wheel_fl = r.wheel_fr = r.wheel_rl = r.wheel_rr = r.speed = speed;
  r.gear = gear;
  r.engine_rpm = engine_rpm(map.maps(), gear, speed);
  std::vector<CanFrame> out;
  for (RaptorMessage m : kRaptorReports) out.push_back(map.report_frame(m, r, counter).frame);
  return out;
}

}  // namespace

TEST(RaptorInterface, SendsEachCommandAtItsRateWithItsCounter) {
  RaptorInterface iface(av21_mapping(), {});
  Sent sent;
  std::vector<std::string> warnings;
  for (int64_t t = 0; t < 1000 * kMs; t += 2 * kMs) {
    if (t % (10 * kMs) == 0 && t > 0) {
      EXPECT_EQ(iface.command({0.1, 0.5, 0, 30}), "");
    }
    const InterfaceStep s = iface.step(t);
    for (const CanFrame& f : s.frames) sent[f.id].push_back(f);
    if (!s.state_change.empty()) warnings.push_back(s.state_change);
    warnings.insert(warnings.end(), s.warnings.begin(), s.warnings.end());
  }
  for (uint32_t id : {1400u, 1401u, 1402u, 1403u, 1404u}) EXPECT_EQ(sent[id].size(), 100u) << id;  // 100 Hz for 1 s
  for (size_t i = 0; i < 100; ++i) {
    EXPECT_EQ(sent[1402][i].data[2], i);      // steering_motor_cmd_counter, byte 2
    EXPECT_EQ(sent[1404][i].data[5], i % 10);  // ct_state_rolling_counter, byte 5: [0|9]
  }
  // The steering and pedal frames of test_raptor.cpp's hand-worked examples (0.1 rad, 50 %).
  EXPECT_EQ(sent[1402][50].data[0], 0xAC);
  EXPECT_EQ(sent[1401][50].data[0], 0x88);
  EXPECT_EQ(sent[1401][50].data[1], 0x13);
  EXPECT_EQ(sent[1403][50].data[0], 1);  // no speed known: first gear
  EXPECT_EQ(sent[1404][50].data[3], 1);  // ct_state, default 1
  // The first frames went out before the first command: throttle off, the stop brake on.
  EXPECT_EQ(sent[1401][0].data[0], 0);
  EXPECT_EQ(sent[1400][0].data[0] | sent[1400][0].data[1] << 8, 1467);  // 0.2445 x 6000 kPa = 1467
  // No report ever came: each named once, after report_timeout_s, with the watchdog's change.
  EXPECT_EQ(warnings.size(), 7u);
  EXPECT_EQ(warnings[0], "commands: WAITING -> ACTIVE");
  EXPECT_EQ(warnings[1], "wheel_speed_report silent: nothing for 0.1 s");
  EXPECT_EQ(iface.counts().frames_sent, 500u);
  EXPECT_EQ(iface.counts().heartbeats, 100u);
}

// Commands stop at 1 s at 20 m/s; the car (the test's) brakes at 6 m/s^2 as the reports show:
// the accelerator goes to 0 and the brake to the stop's pressure 0.1 s later, the heartbeat stops
// 1 s after the car stands, the other commands go on.
TEST(RaptorInterface, StaleCommandsBrakeToAStopThenTheHeartbeatStops) {
  const VehicleCanMapping map = av21_mapping();
  RaptorInterface iface(map, {});
  double speed = 20;
  int64_t stale_at = -1, handover_at = -1, last_heartbeat = -1;
  uint32_t n = 0;
  std::vector<std::string> changes;
  for (int64_t t = 0; t < 8000 * kMs; t += 2 * kMs) {
    if (t < 1000 * kMs && t % (10 * kMs) == 0) iface.command({0.02, 0.3, 0, 20});
    if (t % (10 * kMs) == 0) iface.receive(reports(map, speed, 3, n++), t);
    const InterfaceStep s = iface.step(t);
    if (!s.state_change.empty()) changes.push_back(s.state_change);
    if (iface.watchdog().state() == DbwState::stopping && stale_at < 0) stale_at = t;
    if (iface.watchdog().state() == DbwState::handed_over && handover_at < 0) handover_at = t;
    for (const CanFrame& f : s.frames) {
      if (f.id == 1404) last_heartbeat = t;
      if (stale_at < 0) continue;
      if (f.id == 1401) {
        EXPECT_EQ(f.data[0] | f.data[1] << 8, 0);
      } else if (f.id == 1400) {
        EXPECT_EQ(f.data[0] | f.data[1] << 8, 1467);
      }
    }
    if (stale_at >= 0) speed = std::max(0.0, speed - 6 * 0.002);
  }
  EXPECT_GE(stale_at, 1090 * kMs);  // the last command at 0.99 s, stale past 0.1 s
  EXPECT_LE(stale_at, 1092 * kMs);
  // Under 0.5 m/s after 19.5 / 6 = 3.25 s, heartbeat off 1 s later (the reports come at 100 Hz).
  EXPECT_NEAR(static_cast<double>(handover_at - stale_at) * 1e-9, 3.25 + 1.0, 0.02);
  EXPECT_LT(last_heartbeat, handover_at);
  EXPECT_GE(last_heartbeat, handover_at - 10 * kMs);
  EXPECT_EQ(iface.watchdog().trips(), 1);
  EXPECT_NEAR(iface.watchdog().stop_distance_m(), 20.0 * 20.0 / 12, 0.5);
  EXPECT_EQ(iface.monitor().total_silences(), 0u);
  ASSERT_EQ(changes.size(), 3u);
  EXPECT_EQ(changes[1], "commands: ACTIVE -> STOPPING: none fresh, braking to a stop (at most 4.3 s before the heartbeat stops)");
  // 20^2 / 12 = 33.3 m in 3.25 s, and what the reports, 10 ms apart, add.
  EXPECT_TRUE(std::regex_match(changes[2], std::regex("commands: STOPPING -> HANDED_OVER: stopped in 33\\.[3-5] m and "
                                                      "3\\.2[5-7] s; ct_report's heartbeat stops")))
      << changes[2];
}

TEST(RaptorInterface, CountsWhatIsWrongWithTheReportsAndRefusesBadCommands) {
  const VehicleCanMapping map = av21_mapping();
  RaptorInterface iface(map, {});
  DbwReports r;
  std::vector<CanFrame> frames;
  for (uint32_t c : {0u, 1u, 2u, 5u, 5u}) frames.push_back(map.report_frame(RaptorMessage::steering_report, r, c).frame);
  CanFrame short_frame = frames[0];
  short_frame.length = 2;
  frames.push_back(short_frame);
  CanFrame race_control;
  race_control.id = 1200, race_control.length = 8;
  frames.push_back(race_control);
  const std::vector<std::string> said = iface.receive(frames, 0);
  EXPECT_EQ(said, (std::vector<std::string>{"steering_report: counter skipped 2 (5)", "steering_report: counter repeated 5",
                                            "steering_report: frame of 2 bytes, message steering_report has 3"}));
  const ReportCounts& c = iface.monitor().counts(RaptorMessage::steering_report);
  EXPECT_EQ(c.received, 5u);
  EXPECT_EQ(c.skips, 1u);
  EXPECT_EQ(c.missed, 2u);
  EXPECT_EQ(c.repeats, 1u);
  EXPECT_EQ(c.bad, 1u);
  EXPECT_EQ(iface.counts().other_frames, 1u);
  EXPECT_EQ(iface.command({NAN, 0, 0, 0}), "steer is not a finite number");
  EXPECT_EQ(iface.counts().bad_commands, 1u);
  iface.step(0);
  EXPECT_EQ(iface.watchdog().state(), DbwState::waiting);  // a refused command is no command
}

// The powertrain's report in third at 7 200 rpm: the next gear is commanded; after the interval,
// with fourth engaged at 5 818 rpm, it stays.
TEST(RaptorInterface, ShiftsByThePowertrainReport) {
  const VehicleCanMapping map = av21_mapping();
  RaptorInterface iface(map, {});
  DbwReports r;
  r.gear = 3, r.engine_rpm = 7200;
  iface.receive({map.report_frame(RaptorMessage::pt_report_1, r, 0).frame}, 0);
  iface.command({0, 1, 0, 60});
  EXPECT_EQ(iface.step(0).frames[3].data[0], 3);  // the first step takes the gear engaged
  r.engine_rpm = 7210;
  iface.receive({map.report_frame(RaptorMessage::pt_report_1, r, 0).frame}, 10 * kMs);
  EXPECT_EQ(iface.step(10 * kMs).frames[3].data[0], 4);
  r.gear = 4, r.engine_rpm = 5818;
  iface.receive({map.report_frame(RaptorMessage::pt_report_1, r, 0).frame}, 600 * kMs);
  iface.command({0, 1, 0, 60});
  EXPECT_EQ(iface.step(600 * kMs).frames[3].data[0], 4);
  EXPECT_EQ(iface.shifter().shifts(), 1);
}
