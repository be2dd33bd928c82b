// The Raptor's messages as the vehicle interface speaks them, on the car's own DBC
// (data/vehicle_interface/CAN1-INDY-V14.dbc) and the AV-21's vehicle file: the messages found,
// each command frame and each report worked out by hand (the derivation beside it), the maps and
// their inverse, the rolling counters, the gear shifter, the command watchdog and the report
// monitor.
#include "vehicle_interface/common/dbw_watchdog.hpp"
#include "vehicle_interface/common/gear_shifter.hpp"
#include "vehicle_interface/common/report_monitor.hpp"
#include "vehicle_interface/common/vehicle_can_mapping.hpp"

#include "av21.hpp"
#include "can_frames.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>

using namespace brickyard::vehicle_interface;
using brickyard::motion::Command;

namespace {

const std::string kDbcPath = std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc";

const DbcDatabase& car_dbc() {
  static const DbcReadResult r = load_dbc_file(kDbcPath);
  EXPECT_TRUE(r.ok());
  return *r.database;
}

DbwMaps av21_maps() {
  std::string error;
  const std::optional<DbwMaps> m = dbw_maps(av21_vehicle(), "av21.json", error);
  EXPECT_TRUE(m) << error;
  return m.value_or(DbwMaps{});
}

VehicleCanMapping av21_mapping() {
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(car_dbc(), "CAN1-INDY-V14.dbc", error);
  EXPECT_TRUE(dbc) << error;
  return VehicleCanMapping(std::move(*dbc), av21_maps());
}

std::vector<uint8_t> payload(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.length}; }

// The steer (rad) whose motor angle is `deg` on the AV-21 (ratio 15).
double steer_for_motor_deg(double deg) { return deg / 15 * std::numbers::pi / 180; }

}  // namespace

TEST(RaptorDbc, FindsEveryMessageOfTheCarsDbcWithItsCounter) {
  std::string error;
  const std::optional<RaptorDbc> dbc = RaptorDbc::make(car_dbc(), "CAN1-INDY-V14.dbc", error);
  ASSERT_TRUE(dbc) << error;
  // Ids and counters as `grep '^BO_ 1[34][0-9][0-9] '` and each message's SG_ lines give them.
  const std::pair<RaptorMessage, std::pair<uint32_t, uint32_t>> expected[] = {
      {RaptorMessage::brake_pressure_cmd, {1400, 256}}, {RaptorMessage::accelerator_cmd, {1401, 256}},
      {RaptorMessage::steering_cmd, {1402, 256}},       {RaptorMessage::gear_shift_cmd, {1403, 0}},
      {RaptorMessage::ct_report, {1404, 10}},  // ct_state_rolling_counter [0|9]
      {RaptorMessage::wheel_speed_report, {1300, 0}},   {RaptorMessage::brake_pressure_report, {1301, 256}},
      {RaptorMessage::accelerator_report, {1302, 256}}, {RaptorMessage::steering_report, {1303, 256}},
      {RaptorMessage::pt_report_1, {1340, 0}},          {RaptorMessage::diagnostic_report, {1342, 0}}};
  for (const auto& [m, id_modulus] : expected) {
    EXPECT_EQ(dbc->message(m).id, id_modulus.first) << raptor_name(m);
    EXPECT_EQ(dbc->counter_modulus(m), id_modulus.second) << raptor_name(m);
    EXPECT_EQ(dbc->which(frame_of(id_modulus.first, {})), m);
  }
  EXPECT_FALSE(dbc->which(frame_of(1200, {})));  // race control's: not the interface's
  CanFrame extended = frame_of(1402, {});
  extended.extended = true;
  EXPECT_FALSE(dbc->which(extended));
}

TEST(RaptorDbc, ADbcLackingAMessageOrSignalIsNamedWithFileAndLine) {
  std::string text;
  {
    std::ifstream f(kDbcPath, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(f), {});
  }
  auto error_of = [](const std::string& dbc_text) {
    const DbcReadResult r = parse_dbc(dbc_text, "car.dbc");
    EXPECT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors.front().text());
    std::string error;
    EXPECT_FALSE(RaptorDbc::make(*r.database, "car.dbc", error));
    return error;
  };
  std::string renamed = text;
  renamed.replace(renamed.find("BO_ 1402 steering_cmd:"), 22, "BO_ 1402 steering_cmX:");
  EXPECT_EQ(error_of(renamed),
            "car.dbc: no message steering_cmd (the vehicle interface needs brake_pressure_cmd, accelerator_cmd, steering_cmd, "
            "gear_shift_cmd, ct_report, wheel_speed_report, brake_pressure_report, accelerator_report, steering_report, "
            "pt_report_1, diagnostic_report)");
  std::string no_counter = text;
  auto erase_line = [&](const std::string& start) {
    const size_t at = no_counter.find(start);
    ASSERT_NE(at, std::string::npos) << start;
    no_counter.erase(at, no_counter.find('\n', at) + 1 - at);
  };
  erase_line(" SG_ steering_motor_cmd_counter");
  erase_line("CM_ SG_ 1402 steering_motor_cmd_counter");
  const int line = 1 + static_cast<int>(std::count(no_counter.begin(), no_counter.begin() + no_counter.find("BO_ 1402 "), '\n'));
  EXPECT_EQ(error_of(no_counter), "car.dbc:" + std::to_string(line) + ": message steering_cmd has no signal steering_motor_cmd_counter");
}

// steering_cmd (1402): steering_motor_ang_cmd 0|11@1- (0.5,0), counter 16|8@1+.
//   steer = 85.9437 motor deg / 15 (0.1 rad at the road wheel): 85.9437 / 0.5 = 171.89 -> 172 = 0x0AC:
//   byte 0 = AC, byte 1 bits 0..2 = 000; counter 7 -> byte 2 = 07.   AC 00 07 00 00 00 00 00
//   -0.1 rad: -172 -> 2048 - 172 = 1876 = 0x754: byte 0 = 54, byte 1 = 07; counter 255 -> FF.
TEST(VehicleCanMapping, SteeringCommandByHand) {
  const VehicleCanMapping map = av21_mapping();
  DbwSetpoint s;
  s.actuation = to_actuation({0.1, 0, 0, 0}, map.maps());
  EXPECT_NEAR(s.actuation.steer_motor_deg, 0.1 * 180 / std::numbers::pi * 15, 1e-12);
  PackResult p = map.command_frame(RaptorMessage::steering_cmd, s, 7);
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(p.frame.id, 1402u);
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0xAC, 0x00, 0x07, 0, 0, 0, 0, 0}));
  s.actuation = to_actuation({-0.1, 0, 0, 0}, map.maps());
  p = map.command_frame(RaptorMessage::steering_cmd, s, 255);
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x54, 0x07, 0xFF, 0, 0, 0, 0, 0}));
  // 256 wraps to 0.
  EXPECT_EQ(payload(map.command_frame(RaptorMessage::steering_cmd, s, 256).frame)[2], 0x00);
}

// accelerator_cmd (1401): acc_pedal_cmd 0|16@1- (0.01,0): throttle 0.5 -> 50 % -> 5000 = 0x1388 -> 88 13.
// brake_pressure_cmd (1400): brake_pressure_cmd 0|13@1+ kPa: brake 0.25 x 6000 kPa = 1500 = 0x5DC -> DC 05.
// gear_shift_cmd (1403): desired_gear 0|8@1+: 4 -> 04 (no counter).
// ct_report (1404): ct_state 24|16 = 5 -> bytes 3..4 = 05 00; ct_state_rolling_counter 40|8 [0|9]:
//   12 -> 12 mod 10 = 2 -> byte 5 = 02; veh_num 48|8 = 7 -> byte 6 = 07; the acks 0.
TEST(VehicleCanMapping, PedalGearAndHeartbeatCommandsByHand) {
  const VehicleCanMapping map = av21_mapping();
  DbwSetpoint s;
  s.actuation = to_actuation({0, 0.5, 0.25, 0}, map.maps());
  s.gear = 4, s.ct_state = 5, s.vehicle_number = 7;
  EXPECT_EQ(payload(map.command_frame(RaptorMessage::accelerator_cmd, s, 255).frame),
            (std::vector<uint8_t>{0x88, 0x13, 0xFF, 0, 0, 0, 0, 0}));
  EXPECT_EQ(payload(map.command_frame(RaptorMessage::brake_pressure_cmd, s, 0).frame),
            (std::vector<uint8_t>{0xDC, 0x05, 0x00, 0, 0, 0, 0, 0}));
  EXPECT_EQ(payload(map.command_frame(RaptorMessage::gear_shift_cmd, s, 99).frame), (std::vector<uint8_t>{0x04, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(payload(map.command_frame(RaptorMessage::ct_report, s, 12).frame),
            (std::vector<uint8_t>{0, 0, 0, 0x05, 0x00, 0x02, 0x07, 0}));
}

// The simulated drive-by-wire reads the commands back: each value within half a raw step.
TEST(VehicleCanMapping, CommandsReadBackThroughTheSameMaps) {
  const VehicleCanMapping map = av21_mapping();
  std::mt19937 rng(43);
  std::uniform_real_distribution<double> steer(-0.35, 0.35), pedal(0, 1);
  for (int i = 0; i < 500; ++i) {
    const Command c{steer(rng), pedal(rng), pedal(rng), 0};
    DbwSetpoint sent, got;
    sent.actuation = to_actuation(c, map.maps());
    for (RaptorMessage m : {RaptorMessage::brake_pressure_cmd, RaptorMessage::accelerator_cmd, RaptorMessage::steering_cmd}) {
      const std::optional<ReadFrame> r = map.read_command(map.command_frame(m, sent, static_cast<uint32_t>(i)).frame, got);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->message, m);
      EXPECT_EQ(r->counter, static_cast<uint32_t>(i % 256));
      EXPECT_TRUE(r->error.empty() && r->out_of_range.empty());
    }
    const Command back = from_actuation(got.actuation, map.maps());
    EXPECT_NEAR(back.steer, c.steer, steer_for_motor_deg(0.25) + 1e-12);  // half of 0.5 motor deg
    EXPECT_NEAR(back.throttle, c.throttle, 0.00005 + 1e-12);             // half of 0.01 %
    EXPECT_NEAR(back.brake, c.brake, 0.5 / 6000 + 1e-12);                // half of 1 kPa
  }
  DbwSetpoint s;
  EXPECT_FALSE(map.read_command(frame_of(1300, {0, 0, 0, 0, 0, 0, 0, 0}), s));  // a report is no command
}

// wheel_speed_report (1300), four 16|@1+ (0.1,0) km/h: FL E8 03 = 1000 -> 100.0 km/h, FR D0 07 =
// 2000 -> 200.0 km/h, RL 24 00 = 36 -> 3.6 km/h = 1 m/s, RR 00 00.
// steering_report (1303): 54 07 = -172 -> -86 deg; counter 16|8 = 09.
// brake_pressure_report (1301), 5 bytes: front 0|13 D0 07 = 2000 kPa, rear 16|13 E8 03 = 1000 kPa, counter 32|8 = 2A.
TEST(VehicleCanMapping, ReportsByHand) {
  const VehicleCanMapping map = av21_mapping();
  DbwReports r;
  std::optional<ReadFrame> f = map.read_report(frame_of(1300, {0xE8, 0x03, 0xD0, 0x07, 0x24, 0x00, 0x00, 0x00}), r);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->message, RaptorMessage::wheel_speed_report);
  EXPECT_FALSE(f->counter);
  EXPECT_DOUBLE_EQ(r.wheel_fl, 100.0 / 3.6);
  EXPECT_DOUBLE_EQ(r.wheel_fr, 200.0 / 3.6);
  EXPECT_NEAR(r.wheel_rl, 1.0, 1e-12);
  EXPECT_EQ(r.wheel_rr, 0.0);
  f = map.read_report(frame_of(1303, {0x54, 0x07, 0x09}), r);
  EXPECT_EQ(f->counter, 9u);
  EXPECT_EQ(r.steer_motor_deg, -86.0);
  f = map.read_report(frame_of(1301, {0xD0, 0x07, 0xE8, 0x03, 0x2A}), r);
  EXPECT_EQ(f->counter, 42u);
  EXPECT_EQ(r.brake_front_kpa, 2000.0);
  EXPECT_EQ(r.brake_rear_kpa, 1000.0);
  EXPECT_EQ(r.wheel_rl, 1.0 / 3.6 * 3.6);  // the other reports' fields are untouched
  // Too short: named, nothing taken.
  f = map.read_report(frame_of(1301, {0xFF, 0x07}), r);
  EXPECT_EQ(f->error, "frame of 2 bytes, message brake_pressure_report has 5");
  EXPECT_EQ(r.brake_front_kpa, 2000.0);
}

// pt_report_1 (1340), the frame test_can.cpp derives bit by bit (CanMessage.PacksPowertrainReport...):
// C0 6A 40 C7 53 02 71 20 = run 1, state 1, throttle 42.5 %, gear 3, 7500 rpm, 250.0 km/h, shift status 4.
// diagnostic_report (1342): byte 0 = 01 (sd_system_warning, bit 0), byte 1 = motec_warning 3,
// byte 2 = C0 (adlink_hb_lost bit 22, rc_lost bit 23): diagnostic_bits 0, 14 and 15 set = 0xC001.
TEST(VehicleCanMapping, PowertrainAndDiagnosticReportsByHand) {
  const VehicleCanMapping map = av21_mapping();
  DbwReports r;
  ASSERT_TRUE(map.read_report(frame_of(1340, {0xC0, 0x6A, 0x40, 0xC7, 0x53, 0x02, 0x71, 0x20}), r));
  EXPECT_EQ(r.gear, 3);
  EXPECT_EQ(r.engine_rpm, 7500.0);
  EXPECT_DOUBLE_EQ(r.speed, 250.0 / 3.6);
  EXPECT_EQ(r.throttle_pct, 42.5);
  EXPECT_TRUE(r.engine_running && r.engine_run_switch);
  EXPECT_EQ(r.gear_shift_status, 4);
  ASSERT_TRUE(map.read_report(frame_of(1342, {0x01, 0x03, 0xC0, 0, 0, 0, 0, 0}), r));
  EXPECT_EQ(r.diagnostic_bits, 0xC001u);
  EXPECT_EQ(r.motec_warning, 3);
  EXPECT_EQ(raptor_diagnostic_mask("adlink_hb_lost"), 1u << 14);
  EXPECT_EQ(raptor_diagnostic_mask("rc_lost"), 1u << 15);
  EXPECT_EQ(raptor_diagnostic_mask("nothing"), 0u);
}

// Every report the simulator packs is read back by the car's side as it was (within a raw step).
TEST(VehicleCanMapping, ReportsRoundTrip) {
  const VehicleCanMapping map = av21_mapping();
  DbwReports sent;
  sent.wheel_fl = 80.1, sent.wheel_fr = 80.2, sent.wheel_rl = 79.9, sent.wheel_rr = 0;
  sent.brake_front_kpa = 1234, sent.brake_rear_kpa = 1233, sent.accelerator_pct = 55.5, sent.steer_motor_deg = -120.5;
  sent.throttle_pct = 55.5, sent.gear = 6, sent.engine_rpm = 6543, sent.speed = 80.0, sent.engine_running = true;
  sent.gear_shift_status = 1, sent.diagnostic_bits = 0x4001, sent.motec_warning = 2;
  DbwReports got;
  for (RaptorMessage m : kRaptorReports) {
    const PackResult p = map.report_frame(m, sent, 3);
    ASSERT_TRUE(p.ok()) << raptor_name(m) << ": " << p.error;
    EXPECT_TRUE(p.clamped.empty() && p.out_of_range.empty()) << raptor_name(m);
    ASSERT_TRUE(map.read_report(p.frame, got));
  }
  EXPECT_NEAR(got.wheel_fl, 80.1, 0.05 / 3.6);
  EXPECT_NEAR(got.wheel_rl, 79.9, 0.05 / 3.6);
  EXPECT_EQ(got.brake_front_kpa, 1234);
  EXPECT_EQ(got.accelerator_pct, 55.5);
  EXPECT_EQ(got.steer_motor_deg, -120.5);
  EXPECT_EQ(got.gear, 6);
  EXPECT_EQ(got.engine_rpm, 6543);
  EXPECT_NEAR(got.speed, 80.0, 0.05 / 3.6);
  EXPECT_EQ(got.diagnostic_bits, 0x4001u);
  EXPECT_EQ(got.motec_warning, 2);
}

TEST(DbwMaps, FromTheVehicleFileAndClamped) {
  const DbwMaps m = av21_maps();
  EXPECT_EQ(m.steering_ratio, 15);
  EXPECT_EQ(m.max_brake_pressure_kpa, 6000);
  EXPECT_EQ(m.gear_ratios.size(), 6u);
  const Actuation a = to_actuation({1.0, 1.5, -0.2, 0}, m);  // beyond the car's limits
  EXPECT_NEAR(a.steer_motor_deg, 0.35 * 180 / std::numbers::pi * 15, 1e-9);
  EXPECT_EQ(a.accelerator_pct, 100);
  EXPECT_EQ(a.brake_pressure_kpa, 0);
  EXPECT_EQ(command_problem({NAN, 0, 0, 0}), "steer is not a finite number");
  EXPECT_EQ(command_problem({0, 0, INFINITY, 0}), "brake is not a finite number");
  EXPECT_EQ(command_problem({0.1, 0.2, 0.3, 0}), "");
  // 6 m/s^2 x 815 kg / 20 000 N of brakes = 0.2445.
  EXPECT_NEAR(brake_for_deceleration(m, 6), 0.2445, 1e-12);
  EXPECT_EQ(brake_for_deceleration(m, 100), 1.0);
  // 7500 rpm in sixth: 7500 x 2 pi / 60 / (0.8889 x 3.0) x 0.3 m = 88.36 m/s.
  EXPECT_NEAR(engine_rpm(m, 6, 88.36), 7500, 1.0);
  EXPECT_EQ(engine_rpm(m, 0, 50), 0);
  EXPECT_EQ(engine_rpm(m, 7, 50), 0);
  brickyard::vehicle::Vehicle bare = av21_vehicle();
  bare.drive_by_wire.reset();
  std::string error;
  EXPECT_FALSE(dbw_maps(bare, "car.json", error));
  EXPECT_EQ(error, "car.json: /drive_by_wire: missing: the vehicle interface needs the car's brake pressure, tyre radius and gears");
}

TEST(VehicleCanMapping, NamesASignalTooNarrowForTheCar) {
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(car_dbc(), "CAN1-INDY-V14.dbc", error);
  DbwMaps m = av21_maps();
  EXPECT_EQ(VehicleCanMapping(*dbc, m).capacity_problem("CAN1-INDY-V14.dbc"), "");
  m.max_steer_rad = 0.6;  // 0.6 rad x 15 = 515.7 deg: over the 511.5 deg 11 signed bits at 0.5 carry
  const int line = dbc->signal(RaptorMessage::steering_cmd, "steering_motor_ang_cmd").line;
  EXPECT_EQ(VehicleCanMapping(*dbc, m).capacity_problem("CAN1-INDY-V14.dbc"),
            "CAN1-INDY-V14.dbc:" + std::to_string(line) +
                ": signal steering_motor_ang_cmd carries at most 511.5, the car needs 515.662 deg: max_steer x the steering ratio");
  m = av21_maps();
  m.max_brake_pressure_kpa = 9000;  // 13 bits: 8191
  EXPECT_NE(VehicleCanMapping(*dbc, m).capacity_problem("x.dbc").find("brake_pressure_cmd carries at most 8191"), std::string::npos);
}

TEST(RollingCounter, WrapsAndTellsSkipsRepeatsAndOrder) {
  CounterSender ten(10);
  std::vector<uint32_t> sent;
  for (int i = 0; i < 12; ++i) sent.push_back(ten.next());
  EXPECT_EQ(sent, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 0, 1}));
  CounterChecker c(256);
  uint32_t missed = 99;
  EXPECT_EQ(c.check(254, &missed), CounterStep::first);
  EXPECT_EQ(c.check(255, &missed), CounterStep::in_order);
  EXPECT_EQ(c.check(0, &missed), CounterStep::in_order);  // wraps
  EXPECT_EQ(c.check(0, &missed), CounterStep::repeated);
  EXPECT_EQ(c.check(4, &missed), CounterStep::skipped);
  EXPECT_EQ(missed, 3u);  // 1, 2, 3 lost
  EXPECT_EQ(c.check(2, &missed), CounterStep::skipped);
  EXPECT_EQ(missed, 253u);  // a step back reads as a long skip forward: modulo 256
}

TEST(GearShifter, RefusesRulesThatCannotWork) {
  const DbwMaps m = av21_maps();
  EXPECT_EQ(shift_problem({}, m).what, "");
  EXPECT_EQ(shift_problem({8000, 4000, 0.5, 0}, m).param, "shift_up_rpm");
  EXPECT_EQ(shift_problem({8000, 4000, 0.5, 0}, m).what, "8000 rpm is above the redline, 7500 rpm");
  // The tightest pair: 1.875 / 2.9167: an upshift at 7000 lands at 4500 rpm.
  EXPECT_EQ(shift_problem({7000, 4600, 0.5, 0}, m).what, "4600 rpm must be below 4500 rpm, where an upshift at 7000 rpm lands");
  EXPECT_EQ(shift_problem({7000, 4000, 0.5, 7}, m).what, "gear 7: the car has 6 gears");
  EXPECT_EQ(shift_problem({7000, 4000, 0.5, 6}, m).what, "");
}

// A car accelerating from 10 to 85 m/s and braking back: one gear at a time, never two shifts
// within the interval, the engine never past the redline after a shift has had time, and the
// gear a function of the speed's band (no hunting at a constant speed).
TEST(GearShifter, ShiftsUpAndDownByRpmWithoutHunting) {
  const DbwMaps m = av21_maps();
  GearShifter g({}, m);
  EXPECT_EQ(g.update(0, 0, -1, 10), 1);  // 10 m/s in first: 2785 rpm
  std::vector<int> seen = {1};
  double t = 0, last_shift = 0;
  int gear = 1;
  auto drive = [&](double from, double to, double seconds) {
    for (int i = 1; i <= 1000; ++i) {
      t += seconds / 1000;
      const double v = from + (to - from) * i / 1000;
      const int next = g.update(t, gear, engine_rpm(m, gear, v), v);
      if (next != gear) {
        EXPECT_EQ(std::abs(next - gear), 1);
        EXPECT_GE(t - last_shift, 0.5 - 1e-9);
        last_shift = t, gear = next, seen.push_back(gear);
      }
    }
  };
  drive(10, 85, 30);
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_LE(engine_rpm(m, gear, 85), 7500);
  const int shifts = g.shifts();
  drive(60, 60, 10);  // 60 m/s: 5093 rpm in sixth
  EXPECT_EQ(g.shifts(), shifts);
  drive(60, 12, 20);
  EXPECT_EQ(gear, 1);  // 12 m/s: 3342 rpm in first
  GearShifter fixed({7000, 4000, 0.5, 4}, m);
  EXPECT_EQ(fixed.update(0, 0, -1, 80), 4);
  EXPECT_EQ(fixed.update(5, 4, 9000, 80), 4);
  GearShifter rolling({}, m);
  EXPECT_EQ(rolling.update(0, 0, -1, 60), 4);  // a rolling start at 60 m/s: 6391 rpm in fourth, 7912 in third
}

TEST(DbwWatchdog, DrivesThenStopsThenHandsOver) {
  DbwWatchdog w({0.1, 2.0, 6.0, 0.5, 1.0, 90}, 0.2445);
  const Command c{0.05, 0.7, 0, 40};
  WatchdogOutput o = w.update(0.0, false, {}, 40.0);
  EXPECT_EQ(o.state, DbwState::waiting);
  EXPECT_EQ(o.command.throttle, 0);
  EXPECT_EQ(o.command.brake, 0.2445);
  EXPECT_TRUE(o.heartbeat);
  o = w.update(0.01, true, c, 40.0);
  EXPECT_EQ(o.state, DbwState::active);
  EXPECT_EQ(o.command.throttle, 0.7);
  o = w.update(0.11, false, c, 40.0);  // 0.10 s old: still within the timeout
  EXPECT_EQ(o.state, DbwState::active);
  o = w.update(0.112, false, c, 40.0);  // 0.102 s old: stale
  EXPECT_EQ(o.state, DbwState::stopping);
  EXPECT_EQ(o.command.throttle, 0);
  EXPECT_EQ(o.command.brake, 0.2445);
  EXPECT_EQ(o.command.steer, 0.05);  // held
  EXPECT_EQ(w.trips(), 1);
  o = w.update(0.2, true, c, 39.0);  // back: the stop is called off
  EXPECT_EQ(o.state, DbwState::active);
  EXPECT_EQ(w.recoveries(), 1);
  // Stale at 0.4 (0.2 s old) at 30 m/s: braking at 6 m/s^2 (the test's car), under 0.5 m/s after
  // 29.5 / 6 = 4.917 s, standing 1 s more: the heartbeat stops at 6.317 s, 75 m after the trip.
  EXPECT_EQ(w.update(0.25, false, c, 30.0).state, DbwState::active);
  o = w.update(0.4, false, c, 30.0);
  EXPECT_EQ(o.state, DbwState::stopping);
  int step = 200;  // 2 ms steps from 0.4 s
  double t = 0.4;
  while (step < 4000 && o.state != DbwState::handed_over) {
    t = ++step * 0.002;
    o = w.update(t, false, c, std::max(0.0, 30.0 - 6 * (t - 0.4)));
    if (o.state != DbwState::handed_over) {
      EXPECT_TRUE(o.heartbeat);
    }
  }
  EXPECT_EQ(o.state, DbwState::handed_over);
  EXPECT_FALSE(o.heartbeat);
  EXPECT_NEAR(t, 0.4 + 29.5 / 6 + 1.0, 0.004);
  EXPECT_NEAR(w.stop_time_s(), 29.5 / 6, 0.004);
  EXPECT_NEAR(w.stop_distance_m(), 30.0 * 30.0 / 12, 0.1);
  EXPECT_EQ(o.command.brake, 0.2445);
  // The commands stopped for good at 0.2 s: the gap still open is the longest, the last command's time kept.
  EXPECT_NEAR(w.longest_gap_s(t), t - 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(w.last_command_s(), 0.2);
  o = w.update(t + 0.01, true, c, 0.0);  // latched
  EXPECT_EQ(o.state, DbwState::handed_over);
  EXPECT_FALSE(o.heartbeat);
}

TEST(DbwWatchdog, BoundsTheStopWithoutSpeedAndWhenNoCommandEverCame) {
  DbwWatchdog w({0.1, 2.0, 6.0, 0.5, 1.0, 90}, 0.3);
  WatchdogOutput o;
  for (double t = 0; t <= 2.0; t += 0.5) o = w.update(t, false, {}, std::nullopt);
  EXPECT_EQ(o.state, DbwState::waiting);
  o = w.update(2.01, false, {}, std::nullopt);
  EXPECT_EQ(o.state, DbwState::stopping);
  EXPECT_DOUBLE_EQ(w.stop_bound_s(), 90.0 / 6 + 1);  // no speed: the car's top speed
  o = w.update(2.01 + 15.99, false, {}, std::nullopt);
  EXPECT_EQ(o.state, DbwState::stopping);
  o = w.update(2.01 + 16.01, false, {}, std::nullopt);
  EXPECT_EQ(o.state, DbwState::handed_over);
}

TEST(ReportMonitor, NamesSilencesOnceAndCountsCounterSkips) {
  ReportMonitor mon(100'000'000, {0, 256, 256, 256, 0, 0});
  EXPECT_TRUE(mon.check(0).empty());
  EXPECT_EQ(mon.received(RaptorMessage::steering_report, 10'000'000, 8), "");
  EXPECT_EQ(mon.received(RaptorMessage::steering_report, 20'000'000, 9), "");
  EXPECT_EQ(mon.received(RaptorMessage::steering_report, 30'000'000, 13), "steering_report: counter skipped 3 (13)");
  EXPECT_EQ(mon.received(RaptorMessage::steering_report, 40'000'000, 13), "steering_report: counter repeated 13");
  EXPECT_EQ(mon.received(RaptorMessage::wheel_speed_report, 40'000'000, std::nullopt), "");
  // At 0.1 s from the start the reports never heard fall silent; steering at 0.14 s.
  std::vector<RaptorMessage> fell = mon.check(100'000'001);
  EXPECT_EQ(fell, (std::vector<RaptorMessage>{RaptorMessage::brake_pressure_report, RaptorMessage::accelerator_report,
                                               RaptorMessage::pt_report_1, RaptorMessage::diagnostic_report}));
  EXPECT_TRUE(mon.check(120'000'000).empty());  // said once
  fell = mon.check(140'000'001);
  EXPECT_EQ(fell, (std::vector<RaptorMessage>{RaptorMessage::wheel_speed_report, RaptorMessage::steering_report}));
  EXPECT_EQ(mon.silent_mask(), 0b111111u);
  mon.received(RaptorMessage::steering_report, 150'000'000, 14);
  EXPECT_EQ(mon.silent_mask(), 0b110111u);
  EXPECT_EQ(mon.counts(RaptorMessage::steering_report).skips, 1u);
  EXPECT_EQ(mon.counts(RaptorMessage::steering_report).missed, 3u);
  EXPECT_EQ(mon.counts(RaptorMessage::steering_report).repeats, 1u);
  EXPECT_EQ(mon.counts(RaptorMessage::steering_report).silences, 1u);
  EXPECT_EQ(mon.total_silences(), 6u);
  EXPECT_EQ(mon.check(260'000'000), (std::vector<RaptorMessage>{RaptorMessage::steering_report}));  // silent again
}
