// The DBC reader and signal packing, on the car's own DBC (data/vehicle_interface/CAN1-INDY-V14.dbc,
// New Eagle's Raptor drive-by-wire for the Indy Autonomous Challenge, BSD-2-Clause) and on small
// hand-written files. The counts below were taken from the file with grep, not from our reader:
//   grep -c '^BO_ '                        48 messages (VECTOR__INDEPENDENT_SIG_MSG among them)
//   grep -c '^ SG_ '                       189 signals, 10 of them in VECTOR__INDEPENDENT_SIG_MSG
//   grep '^ SG_' | grep -c '@0'            84 Motorola (the rest, 105, Intel)
//   grep '^ SG_' | grep -c '@[01]-'        27 signed (none of them Motorola: grep -c '@0-' gives 0)
//   grep -c '^CM_ BO_' / '^CM_ SG_'        15 message comments, 55 signal comments (each on its own object)
//   grep -c '^VAL_ '                       2 value tables, 11 names each
// The frames worked out by hand have their derivation beside them.
#include "vehicle_interface/common/can_message.hpp"
#include "vehicle_interface/common/can_signal.hpp"
#include "vehicle_interface/common/dbc.hpp"

#include "can_frames.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace brickyard::vehicle_interface;

namespace {

const std::string kDbcPath = std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc";

const DbcDatabase& car_dbc() {
  static const DbcReadResult result = load_dbc_file(kDbcPath);
  if (!result.ok()) {
    for (const DbcError& e : result.errors) ADD_FAILURE() << e.text();
    static const DbcDatabase empty;
    return empty;
  }
  return *result.database;
}

const DbcMessage& car_message(uint32_t id) {
  const DbcMessage* m = car_dbc().find(id, false);
  EXPECT_NE(m, nullptr) << "message " << id;
  static const DbcMessage none;
  return m ? *m : none;
}

std::vector<uint8_t> payload(const CanFrame& f) { return std::vector<uint8_t>(f.data.begin(), f.data.begin() + f.length); }

// The first error of a hand-written file, as "file:line: what".
std::string first_error(const std::string& text) {
  const DbcReadResult r = parse_dbc(text, "t.dbc");
  return r.errors.empty() ? "no error" : r.errors.front().text();
}

const std::string kHeader = "VERSION \"\"\n\nNS_ :\n\tCM_\n\tVAL_\n\nBS_:\n\nBU_: DBW PC\n\n";

}  // namespace

TEST(Dbc, ReadsTheCarsDbcWithCountsFromTheFile) {
  const DbcReadResult r = load_dbc_file(kDbcPath);
  ASSERT_TRUE(r.ok()) << (r.errors.empty() ? "" : r.errors.front().text());
  const DbcDatabase& db = *r.database;
  EXPECT_EQ(db.messages.size(), 48u);
  EXPECT_EQ(db.signal_count(), 189u);
  size_t motorola = 0, is_signed = 0, message_comments = 0, signal_comments = 0, value_tables = 0, independent = 0;
  for (const DbcMessage& m : db.messages) {
    message_comments += !m.comment.empty();
    if (m.independent_signals) independent += m.signals.size();
    for (const DbcSignal& s : m.signals) {
      motorola += s.byte_order == ByteOrder::kMotorola;
      is_signed += s.is_signed;
      signal_comments += !s.comment.empty();
      value_tables += !s.value_names.empty();
    }
  }
  EXPECT_EQ(motorola, 84u);
  EXPECT_EQ(is_signed, 27u);
  EXPECT_EQ(message_comments, 15u);
  EXPECT_EQ(signal_comments, 55u);
  EXPECT_EQ(value_tables, 2u);
  EXPECT_EQ(independent, 10u);
}

TEST(Dbc, ReadsEachFieldOfASignalMessageCommentAndValueTable) {
  const DbcMessage& steering = car_message(1402);
  EXPECT_EQ(steering.name, "steering_cmd");
  EXPECT_EQ(steering.length, 8u);
  EXPECT_EQ(steering.transmitter, "Vector__XXX");
  EXPECT_EQ(steering.comment, "steering demand from computer to raptor in degrees\r\n");  // the file's CRLF kept
  const DbcSignal* angle = steering.find_signal("steering_motor_ang_cmd");
  ASSERT_NE(angle, nullptr);
  EXPECT_EQ(angle->start_bit, 0u);
  EXPECT_EQ(angle->length, 11u);
  EXPECT_EQ(angle->byte_order, ByteOrder::kIntel);
  EXPECT_TRUE(angle->is_signed);
  EXPECT_EQ(angle->factor, 0.5);
  EXPECT_EQ(angle->offset, 0.0);
  EXPECT_EQ(angle->minimum, -1024.0);
  EXPECT_EQ(angle->maximum, 1023.0);
  EXPECT_EQ(angle->unit, "deg");
  EXPECT_EQ(angle->receivers, std::vector<std::string>{"Vector__XXX"});
  EXPECT_EQ(angle->line, 180);

  const DbcSignal* temp = car_message(1339).find_signal("RR_Tire_Temp_13");
  ASSERT_NE(temp, nullptr);
  EXPECT_EQ(temp->byte_order, ByteOrder::kMotorola);
  EXPECT_EQ(temp->start_bit, 7u);
  EXPECT_EQ(temp->offset, -100.0);
  EXPECT_EQ(temp->maximum, 6453.5);

  const DbcSignal* aim = car_message(1343).find_signal("driver_traction_aim_swicth_fbk");
  ASSERT_NE(aim, nullptr);
  ASSERT_EQ(aim->value_names.size(), 11u);
  EXPECT_EQ(aim->value_names.at(-1), "Default");
  EXPECT_EQ(aim->value_names.at(9), "Nine");

  const DbcMessage* holder = car_dbc().find("VECTOR__INDEPENDENT_SIG_MSG");
  ASSERT_NE(holder, nullptr);
  EXPECT_TRUE(holder->independent_signals);
  EXPECT_EQ(car_dbc().find(holder->id, holder->extended), nullptr);  // never matched to a frame
  EXPECT_FALSE(pack_message(*holder, {}).ok());
}

// steering_cmd (1402), Intel, signed: steering_motor_ang_cmd 0|11@1- (0.5,0), counter 16|8@1+.
//   -100.5 deg / 0.5 = raw -201; 11-bit two's complement 2048 - 201 = 1847 = 0x737 = 111 0011 0111b.
//   Intel from bit 0: byte 0 takes the low 8 bits, 0x37; byte 1 bits 0..2 the top 3, 0x07.
//   counter 5 from bit 16: byte 2 = 0x05.                   -> 37 07 05 00 00 00 00 00
TEST(CanMessage, PacksSteeringCommandIntelSignedByHand) {
  const PackResult p = pack_message(car_message(1402), {{"steering_motor_ang_cmd", -100.5}, {"steering_motor_cmd_counter", 5}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(p.frame.id, 1402u);
  EXPECT_FALSE(p.frame.extended);
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x37, 0x07, 0x05, 0, 0, 0, 0, 0}));
  EXPECT_TRUE(p.clamped.empty());
  EXPECT_TRUE(p.out_of_range.empty());
  // Bits 11..15 belong to no signal: set, they change nothing on the way back.
  const UnpackResult u = unpack_message(car_message(1402), frame_of(1402, {0x37, 0xFF, 0x05, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(u.ok()) << u.error;
  EXPECT_EQ(u.values.at("steering_motor_ang_cmd"), -100.5);
  EXPECT_EQ(u.values.at("steering_motor_cmd_counter"), 5.0);
}

// brake_pressure_cmd (1400), Intel, unsigned: brake_pressure_cmd 0|13@1+ (1,0) [0|8191].
//   3000 kPa = 0xBB8: byte 0 = 0xB8, byte 1 = 0x0B (bits 8..12); counter 200 = 0xC8 in byte 2.
TEST(CanMessage, PacksBrakeCommandIntelUnsignedByHand) {
  const PackResult p = pack_message(car_message(1400), {{"brake_pressure_cmd", 3000}, {"brk_pressure_cmd_counter", 200}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0xB8, 0x0B, 0xC8, 0, 0, 0, 0, 0}));
}

// base_to_car_summary (1200), Intel, unsigned nibbles. Bytes 93 24 50 0C D2 04 00 00:
//   byte 0 = 0x93: heartbeat (bits 0..3) 3, track_flag (4..7) 9; byte 1 = 0x24: veh_flag 4,
//   veh_rank 2; round_target_speed (16|8) 0x50 = 80 mph; lap_count (24|8) 0x0C = 12;
//   lap_distance (32|16) bytes 4..5 little endian 0x04D2 = 1234 m.
TEST(CanMessage, UnpacksRaceControlSummaryByHandAndPacksItBack) {
  const std::vector<uint8_t> bytes = {0x93, 0x24, 0x50, 0x0C, 0xD2, 0x04, 0, 0};
  const UnpackResult u = unpack_message(car_message(1200), frame_of(1200, bytes));
  ASSERT_TRUE(u.ok()) << u.error;
  const SignalValues expected = {{"base_to_car_heartbeat", 3}, {"track_flag", 9},         {"veh_flag", 4},
                                 {"veh_rank", 2},              {"round_target_speed", 80}, {"lap_count", 12},
                                 {"lap_distance", 1234}};
  EXPECT_EQ(u.values, expected);
  EXPECT_TRUE(u.out_of_range.empty());  // [0|0]: no declared range
  EXPECT_EQ(payload(pack_message(car_message(1200), expected).frame), bytes);
}

// Tire_Temp_RR_4 (1339), Motorola, unsigned, (0.1,-100): the start bit is the most significant
// bit; 7|16@0+ takes byte 0 (bit 7 down) then byte 1: a big-endian 16-bit word in bytes 0..1
// (_13), 23 in bytes 2..3 (_14), 39 in 4..5 (_15), 55 in 6..7 (_16).
//   25.0 degC: (25 + 100) / 0.1 = 1250 = 0x04E2 -> 04 E2;  -100: raw 0 -> 00 00;
//   6453.5: 65535 -> FF FF;  85.3: 1853 = 0x073D -> 07 3D.
TEST(CanMessage, PacksTireTemperaturesMotorolaUnsignedByHand) {
  const PackResult p = pack_message(car_message(1339), {{"RR_Tire_Temp_13", 25.0},
                                                        {"RR_Tire_Temp_14", -100.0},
                                                        {"RR_Tire_Temp_15", 6453.5},
                                                        {"RR_Tire_Temp_16", 85.3}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x04, 0xE2, 0x00, 0x00, 0xFF, 0xFF, 0x07, 0x3D}));
  EXPECT_TRUE(p.clamped.empty());
}

// pt_report_1 (1340), Motorola signals that cross bytes off their boundaries. Numbering the bits
// big-endian from byte 0's bit 7 (index 0) on, a start bit s is index (s/8)*8 + 7 - s%8 and each
// signal runs on from there: engine_run_switch 7 -> 0, engine_state 6 -> 1, throttle_position
// 5|16 -> 2..17, current_gear 21|8 -> 18..25, engine_speed_rpm 29|16 -> 26..41,
// vehicle_speed_kmph 45|16 -> 42..57, gear_shift_status 61|3 -> 58..60; 61..63 unused.
//   run 1, state 1, throttle 42.5 % -> 425 = 0000000110101001, gear 3 -> 00000011,
//   rpm 7500 = 0001110101001100, speed 250.0 kmph -> 2500 = 0000100111000100, shift 4 -> 100:
//   11000000 01101010 01000000 11000111 01010011 00000010 01110001 00100000
//   = C0 6A 40 C7 53 02 71 20
TEST(CanMessage, PacksPowertrainReportMotorolaAcrossBytesByHand) {
  const SignalValues values = {{"engine_run_switch", 1}, {"engine_state", 1},       {"throttle_position", 42.5},
                               {"current_gear", 3},      {"engine_speed_rpm", 7500}, {"vehicle_speed_kmph", 250.0},
                               {"gear_shift_status", 4}};
  const PackResult p = pack_message(car_message(1340), values);
  ASSERT_TRUE(p.ok()) << p.error;
  const std::vector<uint8_t> bytes = {0xC0, 0x6A, 0x40, 0xC7, 0x53, 0x02, 0x71, 0x20};
  EXPECT_EQ(payload(p.frame), bytes);
  const UnpackResult u = unpack_message(car_message(1340), frame_of(1340, bytes));
  ASSERT_TRUE(u.ok()) << u.error;
  EXPECT_EQ(u.values, values);
}

// accelerator_cmd (1401), Intel signed with a factor: -12.34 % / 0.01 = -1234;
// 65536 - 1234 = 64302 = 0xFB2E -> 2E FB.
TEST(CanMessage, PacksAcceleratorCommandIntelSignedScaledByHand) {
  const PackResult p = pack_message(car_message(1401), {{"acc_pedal_cmd", -12.34}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x2E, 0xFB, 0, 0, 0, 0, 0, 0}));
}

// The DBC has no signed Motorola signal: this one is written for the test.
//   s : 3|12@0- (0.25,0): MSB at byte 0 bit 3 (index 4), 12 bits -> indices 4..15: byte 0's
//   low nibble and byte 1. -50.25 / 0.25 = -201 -> 4096 - 201 = 3895 = 0xF37:
//   byte 0 = xxxx1111 -> 0x0F, byte 1 = 0x37.
TEST(CanMessage, PacksSignedMotorolaByHand) {
  const DbcReadResult r = parse_dbc(kHeader + "BO_ 300 m: 2 DBW\n SG_ s : 3|12@0- (0.25,0) [-512|511.75] \"\" PC\n", "t.dbc");
  ASSERT_TRUE(r.ok()) << r.errors.front().text();
  const DbcMessage& m = r.database->messages.front();
  const PackResult p = pack_message(m, {{"s", -50.25}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x0F, 0x37}));
  EXPECT_EQ(unpack_message(m, frame_of(300, {0xFF, 0x37})).values.at("s"), -50.25);  // bits 4..7 of byte 0 are not s's
}

TEST(CanMessage, RoundsToTheNearestRawValue) {
  const DbcMessage& steering = car_message(1402);
  EXPECT_EQ(payload(pack_message(steering, {{"steering_motor_ang_cmd", -100.26}}).frame)[0], 0x37);  // -200.52 -> -201
  EXPECT_EQ(payload(pack_message(steering, {{"steering_motor_ang_cmd", -100.24}}).frame)[0], 0x38);  // -200.48 -> -200
  // Halves go away from zero: 2999.5 -> 3000 (0xBB8), 0.5 -> 1.
  EXPECT_EQ(payload(pack_message(car_message(1400), {{"brake_pressure_cmd", 2999.5}}).frame)[0], 0xB8);
  EXPECT_EQ(payload(pack_message(car_message(1400), {{"brake_pressure_cmd", 0.5}}).frame)[0], 0x01);
}

// A value beyond what the signal carries is written at the nearest end and named; a value
// outside the declared [min|max] is named too.
TEST(CanMessage, ClampsAndReportsValuesOutsideTheSignal) {
  // steering_motor_ang_cmd declares [-1024|1023] deg but its 11 bits at 0.5 carry -512..511.5:
  // 600 is in the declared range, clamped to raw 1023 = 0x3FF (FF 03).
  PackResult p = pack_message(car_message(1402), {{"steering_motor_ang_cmd", 600}});
  EXPECT_EQ(p.clamped, std::vector<std::string>{"steering_motor_ang_cmd"});
  EXPECT_TRUE(p.out_of_range.empty());
  EXPECT_EQ(payload(p.frame)[0], 0xFF);
  EXPECT_EQ(payload(p.frame)[1], 0x03);
  // 2000 is outside both.
  p = pack_message(car_message(1402), {{"steering_motor_ang_cmd", 2000}});
  EXPECT_EQ(p.clamped, std::vector<std::string>{"steering_motor_ang_cmd"});
  EXPECT_EQ(p.out_of_range, std::vector<std::string>{"steering_motor_ang_cmd"});
  // acc_pedal_cmd [-150|655.35]: -200 -> clamped to -150.00 = raw -15000 = 0xC568 (68 C5).
  p = pack_message(car_message(1401), {{"acc_pedal_cmd", -200}});
  EXPECT_EQ(p.clamped, std::vector<std::string>{"acc_pedal_cmd"});
  EXPECT_EQ(p.out_of_range, std::vector<std::string>{"acc_pedal_cmd"});
  EXPECT_EQ(payload(p.frame)[0], 0x68);
  EXPECT_EQ(payload(p.frame)[1], 0xC5);
  // ct_state_rolling_counter [0|9] in 8 bits: 12 -> 9.
  p = pack_message(car_message(1404), {{"ct_state_rolling_counter", 12}});
  EXPECT_EQ(p.clamped, std::vector<std::string>{"ct_state_rolling_counter"});
  EXPECT_EQ(payload(p.frame)[5], 9);
  // Within half a step of the maximum: written as the maximum, not clamped, but still named.
  p = pack_message(car_message(1400), {{"brake_pressure_cmd", 8191.2}});
  EXPECT_TRUE(p.clamped.empty());
  EXPECT_EQ(p.out_of_range, std::vector<std::string>{"brake_pressure_cmd"});
}

TEST(CanMessage, ReportsReceivedValuesOutsideTheirRange) {
  // wheel_speed_report: wheel_speed_FL 0|16@1+ (0.1,0) [0|340]; raw 5000 (88 13) = 500 kmph.
  const UnpackResult u = unpack_message(car_message(1300), frame_of(1300, {0x88, 0x13, 0x10, 0x0D, 0, 0, 0, 0}));
  ASSERT_TRUE(u.ok()) << u.error;
  EXPECT_EQ(u.values.at("wheel_speed_FL"), 500.0);
  EXPECT_DOUBLE_EQ(u.values.at("wheel_speed_FR"), 334.4);  // 10 0D: 0x0D10 = 3344
  EXPECT_EQ(u.out_of_range, std::vector<std::string>{"wheel_speed_FL"});
  EXPECT_EQ(check_range(*car_message(1300).find_signal("wheel_speed_FL"), 340.0), RangeCheck::kInside);
  EXPECT_EQ(check_range(*car_message(1300).find_signal("wheel_speed_FL"), 340.1), RangeCheck::kAboveMaximum);
  EXPECT_EQ(check_range(*car_message(1300).find_signal("wheel_speed_FL"), -0.1), RangeCheck::kBelowMinimum);
}

TEST(CanMessage, RefusesWhatItCannotPackOrUnpack) {
  const DbcMessage& brake = car_message(1400);
  EXPECT_EQ(pack_message(brake, {{"brake_pressure", 1}}).error, "message brake_pressure_cmd has no signal brake_pressure");
  EXPECT_EQ(pack_message(brake, {{"brake_pressure_cmd", NAN}}).error, "signal brake_pressure_cmd: value is not a finite number");
  EXPECT_EQ(unpack_message(brake, frame_of(1401, std::vector<uint8_t>(8))).error, "frame 1401 is not message brake_pressure_cmd");
  EXPECT_EQ(unpack_message(brake, frame_of(1400, std::vector<uint8_t>(7))).error,
            "frame of 7 bytes, message brake_pressure_cmd has 8");
  CanFrame remote = frame_of(1400, std::vector<uint8_t>(8));
  remote.remote = true;
  EXPECT_EQ(unpack_message(brake, remote).error, "frame for message brake_pressure_cmd is a remote request: no data");
}

// Every message of the car's DBC, 200 times, every signal a random value inside what it carries
// (its [min|max] narrowed to its bits): packed and unpacked, each value comes back within half a
// raw step, unclamped and in range; and the raw bits chosen come back exactly.
TEST(CanMessage, EveryCarMessageRoundTripsRandomValues) {
  std::mt19937_64 rng(20240611);
  size_t checked = 0;
  for (const DbcMessage& m : car_dbc().messages) {
    if (m.independent_signals) continue;
    for (int trial = 0; trial < 200; ++trial) {
      SignalValues values;
      for (const DbcSignal& s : m.signals) {
        const RawRange range = raw_range(s).value();
        const double low = range.lowest * s.factor + s.offset, high = range.highest * s.factor + s.offset;
        values[s.name] = std::uniform_real_distribution<double>(std::min(low, high), std::max(low, high))(rng);
      }
      const PackResult p = pack_message(m, values);
      ASSERT_TRUE(p.ok()) << m.name << ": " << p.error;
      EXPECT_TRUE(p.clamped.empty()) << m.name << " " << p.clamped.front();
      EXPECT_TRUE(p.out_of_range.empty()) << m.name << " " << p.out_of_range.front();
      const UnpackResult u = unpack_message(m, p.frame);
      ASSERT_TRUE(u.ok()) << m.name << ": " << u.error;
      ASSERT_EQ(u.values.size(), values.size());
      for (const DbcSignal& s : m.signals) {
        EXPECT_NEAR(u.values.at(s.name), values.at(s.name), std::fabs(s.factor) * 0.5 + 1e-9) << m.name << "." << s.name;
        const uint64_t raw = physical_to_raw(s, u.values.at(s.name))->raw;
        EXPECT_EQ(read_raw(s, p.frame.data.data()), raw) << m.name << "." << s.name;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 179u * 200u);  // 189 signals less the 10 no frame carries
}

// Each raw bit of a signal lands where locate_raw_bit says and nowhere else: a single bit set at a
// time, for every signal of the car's DBC.
TEST(CanSignal, EachRawBitLandsOnItsOwnPayloadBit) {
  for (const DbcMessage& m : car_dbc().messages) {
    if (m.independent_signals) continue;
    for (const DbcSignal& s : m.signals) {
      for (uint32_t j = 0; j < s.length; ++j) {
        uint8_t bytes[64] = {};
        write_raw(s, uint64_t{1} << j, bytes);
        const BitLocation at = locate_raw_bit(s, j);
        int set = 0;
        for (uint8_t b : bytes) set += std::popcount(b);
        EXPECT_EQ(set, 1);
        EXPECT_EQ(bytes[at.byte], 1u << at.bit) << s.name << " bit " << j;
        EXPECT_EQ(read_raw(s, bytes), uint64_t{1} << j);
      }
    }
  }
}

TEST(CanSignal, ReadsIeeeFloatSignals) {
  // 1.5f = 0x3FC00000 (sign 0, exponent 127, mantissa 0x400000); Intel: 00 00 C0 3F.
  const DbcReadResult r = parse_dbc(kHeader + "BO_ 10 m: 8 DBW\n SG_ f : 0|32@1- (2,0) [0|0] \"\" PC\n"
                                              " SG_ d : 32|32@1+ (1,0) [0|0] \"\" PC\n\nSIG_VALTYPE_ 10 f : 1;\n", "t.dbc");
  ASSERT_TRUE(r.ok()) << r.errors.front().text();
  const DbcMessage& m = r.database->messages.front();
  EXPECT_EQ(m.signals[0].value_type, SignalValueType::kFloat32);
  const PackResult p = pack_message(m, {{"f", 3.0}});  // 3.0 / factor 2 = 1.5
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x00, 0x00, 0xC0, 0x3F, 0, 0, 0, 0}));
  EXPECT_EQ(unpack_message(m, p.frame).values.at("f"), 3.0);
}

TEST(CanSignal, HandlesSixtyFourBitSignals) {
  const DbcReadResult r = parse_dbc(kHeader + "BO_ 11 m: 8 DBW\n SG_ s : 0|64@1- (1,0) [0|0] \"\" PC\n", "t.dbc");
  ASSERT_TRUE(r.ok()) << r.errors.front().text();
  const DbcSignal& s = r.database->messages.front().signals.front();
  EXPECT_EQ(raw_to_physical(s, ~uint64_t{0}), -1.0);
  EXPECT_EQ(physical_to_raw(s, -1.0)->raw, ~uint64_t{0});
  EXPECT_TRUE(physical_to_raw(s, 1e30)->clamped);
  EXPECT_EQ(physical_to_raw(s, 1e30)->raw, uint64_t{0x7FFFFFFFFFFFFC00});  // the largest double below 2^63
}

TEST(Dbc, ReadsExtendedIdsAndMultiplexedSignals) {
  // 2566844926 = 0x80000000 + 0x18FEF1FE: bit 31 marks the 29-bit id 0x18FEF1FE.
  const std::string text = kHeader +
                           "BO_ 2566844926 j1939: 8 DBW\n SG_ speed : 8|16@1+ (0.00390625,0) [0|250.996] \"km/h\" PC\n\n"
                           "BO_ 500 muxed: 8 DBW\n SG_ page M : 0|8@1+ (1,0) [0|0] \"\" PC\n"
                           " SG_ a m0 : 8|16@1+ (1,0) [0|0] \"\" PC\n SG_ b m1 : 8|8@1+ (1,0) [0|0] \"\" PC\n";
  const DbcReadResult r = parse_dbc(text, "t.dbc");
  ASSERT_TRUE(r.ok()) << r.errors.front().text();
  const DbcMessage* j1939 = r.database->find(0x18FEF1FE, true);
  ASSERT_NE(j1939, nullptr);
  EXPECT_EQ(r.database->find(0x18FEF1FE, false), nullptr);
  EXPECT_TRUE(pack_message(*j1939, {{"speed", 100}}).frame.extended);

  const DbcMessage& muxed = *r.database->find(500, false);
  EXPECT_TRUE(muxed.signals[0].is_multiplexer);
  EXPECT_EQ(muxed.signals[2].multiplexer_value, 1u);
  const PackResult p = pack_message(muxed, {{"page", 1}, {"b", 0xAB}});
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(payload(p.frame), (std::vector<uint8_t>{0x01, 0xAB, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(unpack_message(muxed, p.frame).values, (SignalValues{{"page", 1}, {"b", 0xAB}}));
  EXPECT_EQ(pack_message(muxed, {{"page", 1}, {"a", 3}}).error, "signal a is present when the multiplexer reads 0, not 1");
}

// Hostile or broken files: each refused with the file, the line and what is wrong.
TEST(Dbc, RefusesBadLinesNamingFileAndLine) {
  const std::string bo = kHeader + "BO_ 100 m: 8 DBW\n";  // the BO_ line is line 11
  EXPECT_EQ(first_error(bo + " SG_ X : 0|0@1+ (1,0) [0|0] \"\" PC\n"), "t.dbc:12: signal X: length 0 (1 to 64 bits)");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|65@1+ (1,0) [0|0] \"\" PC\n"), "t.dbc:12: signal X: length 65 (1 to 64 bits)");
  EXPECT_EQ(first_error(bo + " SG_ X : 60|8@1+ (1,0) [0|0] \"\" PC\n"), "t.dbc:12: signal X: bits outside the message's 8 bytes");
  EXPECT_EQ(first_error(bo + " SG_ X : 56|16@0+ (1,0) [0|0] \"\" PC\n"), "t.dbc:12: signal X: bits outside the message's 8 bytes");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@2+ (1,0) [0|0] \"\" PC\n"),
            "t.dbc:12: signal X: expected the byte order, 1 (Intel) or 0 (Motorola), found '2'");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (0,0) [0|0] \"\" PC\n"), "t.dbc:12: signal X: factor must be a non-zero number");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (1,0) [10|5] \"\" PC\n"),
            "t.dbc:12: signal X: range [min|max] must be two numbers, min <= max");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|4@1+ (1,0) [1000|2000] \"\" PC\n"),
            "t.dbc:12: signal X: range [min|max] lies outside what its 4 bits carry");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\n SG_ Y : 4|8@1+ (1,0) [0|0] \"\" PC\n"),
            "t.dbc:13: message m: signal Y: shares bits with X");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\n SG_ X : 8|8@1+ (1,0) [0|0] \"\" PC\n"),
            "t.dbc:13: signal X: defined twice in message m");
  EXPECT_EQ(first_error(bo + " SG_ X q : 0|8@1+ (1,0) [0|0] \"\" PC\n"),
            "t.dbc:12: signal X: multiplexer mark 'q' is none of M, m<value>, m<value>M");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (1,0) [0|0] PC\n"), "t.dbc:12: signal X: expected the unit (a string), found 'PC'");
  EXPECT_EQ(first_error(bo + " SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\nSIG_VALTYPE_ 100 X : 1;\n"),
            "t.dbc:13: signal X: a float (SIG_VALTYPE_ 1) needs 32 bits");
  EXPECT_EQ(first_error(kHeader + " SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\n"),
            "t.dbc:11: signal outside a message (SG_ lines follow their BO_ line)");
}

TEST(Dbc, RefusesBadMessagesAndStatements) {
  EXPECT_EQ(first_error(kHeader + "BO_ 4096 m: 8 DBW\n"),
            "t.dbc:11: message m: standard id 4096 over 2047 (an extended id is written with bit 31 set: 2147487744)");
  EXPECT_EQ(first_error(kHeader + "BO_ 4294967295 m: 8 DBW\n"), "t.dbc:11: message m: extended id 2147483647 wider than 29 bits");
  EXPECT_EQ(first_error(kHeader + "BO_ 1 m: 9 DBW\n"), "t.dbc:11: message m: length 9 is not a CAN (0 to 8) or CAN FD length");
  EXPECT_EQ(first_error(kHeader + "BO_ 1 m: 8 DBW\nBO_ 1 n: 8 DBW\n"), "t.dbc:12: message n: id 1 given to another message before");
  // A message refused for its name leaves no trace its id could be found by (found by fuzz_dbc).
  const DbcReadResult twice = parse_dbc(kHeader + "BO_ 1 m: 8 DBW\nBO_ 2 m: 8 DBW\nCM_ BO_ 2 \"x\";\n", "t.dbc");
  ASSERT_EQ(twice.errors.size(), 2u);
  EXPECT_EQ(twice.errors[0].text(), "t.dbc:12: message m: name given to another message before");
  EXPECT_EQ(twice.errors[1].text(), "t.dbc:13: comment for message 2, which no BO_ defines");
  EXPECT_EQ(first_error(kHeader + "BO_ -1 m: 8 DBW\n"), "t.dbc:11: expected the message id (an unsigned integer), found '-1'");
  EXPECT_EQ(first_error(kHeader + "CM_ BO_ 77 \"no such message\";\n"),
            "t.dbc:11: comment for message 77, which no BO_ defines");
  EXPECT_EQ(first_error(kHeader + "BO_ 1 m: 8 DBW\nVAL_ 1 nope 0 \"off\" ;\n"),
            "t.dbc:12: value names for signal nope, which message m does not have");
  EXPECT_EQ(first_error(kHeader + "BO_ 1 m: 8 DBW\n SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\nVAL_ 1 X 0 \"a\" 0 \"b\" ;\n"),
            "t.dbc:13: signal X: value 0 named twice");
  EXPECT_EQ(first_error(kHeader + "BO_ 1 m: 8 DBW\n SG_ X : 0|8@1+ (1,0) [0|0] \"\" PC\nCM_ SG_ 1 X \"never closed;\n\n"),
            "t.dbc:13: expected the comment (a string), found string not closed");
  EXPECT_EQ(first_error(kHeader + "CM_ \"never closed;\n\n"),
            "t.dbc:11: expected BU_, BO_, SG_, EV_ or the comment, found string not closed");
  EXPECT_EQ(first_error(kHeader + "BA_DEF_ \"x\" INT 0 1\n"), "t.dbc:11: BA_DEF_ not ended by ';'");
  EXPECT_EQ(first_error(kHeader + "FOO_ 1 2 3;\n"), "t.dbc:11: unknown keyword 'FOO_'");
  EXPECT_EQ(first_error(kHeader + "\x01\n"), "t.dbc:11: expected a keyword, found byte \\x01");
}

TEST(Dbc, StaysBoundedOnHostileInput) {
  std::string many_bad;
  for (int i = 0; i < 5000; ++i) many_bad += "BO_ x\n";
  const DbcReadResult r = parse_dbc(many_bad, "t.dbc");
  EXPECT_EQ(r.errors.size(), 20u);
  EXPECT_EQ(r.errors.back().line, 20);
  DbcLimits small;
  small.max_file_bytes = 100;
  EXPECT_EQ(parse_dbc(std::string(101, ' '), "t.dbc", small).errors.front().text(),
            "t.dbc:0: file of 101 bytes or more, over the limit of 100");
  EXPECT_EQ(load_dbc_file("/nonexistent/x.dbc").errors.front().text(),
            "x.dbc:0: /nonexistent/x.dbc: cannot be opened (No such file or directory)");
  // A device or a FIFO where the DBC should be: refused unread (a FIFO's read waits for ever).
  EXPECT_EQ(load_dbc_file("/dev/null").errors.front().text(), "null:0: /dev/null: not a regular file");
  const std::string fifo = testing::TempDir() + "/brickyard_dbc.fifo";
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(load_dbc_file(fifo).errors.front().text(), "brickyard_dbc.fifo:0: " + fifo + ": not a regular file");
  std::remove(fifo.c_str());
  // Every prefix of the car's file either reads or fails with errors; none crashes.
  const std::string text = [] {
    std::string all;
    FILE* f = std::fopen(kDbcPath.c_str(), "rb");
    char buf[4096];
    size_t n;
    while (f && (n = std::fread(buf, 1, sizeof buf, f)) > 0) all.append(buf, n);
    if (f) std::fclose(f);
    return all;
  }();
  for (size_t cut = 0; cut < text.size(); cut += 97) (void)parse_dbc(std::string_view(text).substr(0, cut), "cut.dbc");
}
