// Race control on the bus (common/race_control.hpp): base_to_car_summary read from frames worked
// out by hand from the car's DBC, bit for bit both ways; the flag codes; the heartbeat watched;
// and the car's side (RaptorInterface) reading it and looping the codes back in ct_report's acks.
#include "vehicle_interface/common/race_control.hpp"
#include "vehicle_interface/common/raptor_interface.hpp"

#include "av21.hpp"

#include <gtest/gtest.h>

#include <map>

using namespace brickyard::vehicle_interface;

namespace {

const DbcDatabase& car_dbc() {
  static const DbcReadResult read = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  return *read.database;
}

RaceControlDbc race_dbc() {
  std::string error;
  std::optional<RaceControlDbc> rc = RaceControlDbc::make(car_dbc(), "CAN1-INDY-V14.dbc", error);
  EXPECT_TRUE(rc) << error;
  return *rc;
}

CanFrame frame(uint32_t id, std::vector<uint8_t> bytes) {
  CanFrame f;
  f.id = id;
  f.length = static_cast<uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), f.data.begin());
  return f;
}

std::vector<uint8_t> payload(const CanFrame& f) { return {f.data.begin(), f.data.begin() + f.length}; }

constexpr int64_t kMs = 1'000'000;

}  // namespace

// base_to_car_summary (1200), Intel, unsigned (CAN1-INDY-V14.dbc lines 263-270):
//   base_to_car_heartbeat 0|4 = 5, track_flag 4|4 = 3 (yellow): byte 0 = 0x35;
//   veh_flag 8|4 = 1 (none), veh_rank 12|4 = 2: byte 1 = 0x21;
//   round_target_speed 16|8 = 60 mph: byte 2 = 0x3C; lap_count 24|8 = 7: byte 3 = 0x07;
//   lap_distance 32|16 = 2500 m = 0x09C4: bytes 4..5 = C4 09; bytes 6..7 unused.
TEST(RaceControlDbc, ReadsAndPacksTheSummaryBitForBitByHand) {
  const RaceControlDbc rc = race_dbc();
  const std::vector<uint8_t> bytes = {0x35, 0x21, 0x3C, 0x07, 0xC4, 0x09, 0, 0};
  const RaceSummaryRead r = rc.read(frame(1200, bytes));
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.summary.heartbeat, 5);
  EXPECT_EQ(r.summary.track_code, 3);
  EXPECT_EQ(r.summary.vehicle_code, 1);
  EXPECT_EQ(r.summary.rank, 2);
  EXPECT_EQ(r.summary.target_mph, 60);
  EXPECT_EQ(r.summary.lap, 7);
  EXPECT_EQ(r.summary.lap_distance_m, 2500);
  const PackResult p = rc.pack(r.summary);
  ASSERT_TRUE(p.ok()) << p.error;
  EXPECT_EQ(p.frame.id, 1200u);
  EXPECT_EQ(payload(p.frame), bytes);
  EXPECT_EQ(rc.heartbeat_modulus(), 16u);  // 4 bits, no declared range
  // The heartbeat is packed modulo its 16 values: 21 is 5.
  RaceSummary wrapped = r.summary;
  wrapped.heartbeat = 21;
  EXPECT_EQ(payload(rc.pack(wrapped).frame), bytes);
  // A frame cut short is refused, not read.
  EXPECT_NE(rc.read(frame(1200, {0x35, 0x21, 0x3C})).error, "");
  EXPECT_TRUE(rc.is_summary(frame(1200, bytes)));
  EXPECT_FALSE(rc.is_summary(frame(1404, bytes)));
}

TEST(RaceControlDbc, ADbcWithoutTheSummaryOrOneOfItsSignalsIsNamed) {
  std::string error;
  const DbcReadResult none = parse_dbc("VERSION \"\"\nBO_ 1404 ct_report: 8 X\n SG_ veh_sig_ack : 0|8@1+ (1,0) [0|0] \"\" X\n", "t.dbc");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(RaceControlDbc::make(*none.database, "t.dbc", error));
  EXPECT_EQ(error, "t.dbc: no message base_to_car_summary (race control's flags: the vehicle interface needs it)");
  const DbcReadResult partial = parse_dbc(
      "VERSION \"\"\n\nBO_ 1200 base_to_car_summary: 8 X\n SG_ base_to_car_heartbeat : 0|4@1+ (1,0) [0|0] \"\" X\n"
      " SG_ track_flag : 4|4@1+ (1,0) [0|0] \"\" X\n", "t.dbc");
  ASSERT_TRUE(partial.ok());
  EXPECT_FALSE(RaceControlDbc::make(*partial.database, "t.dbc", error));
  EXPECT_EQ(error, "t.dbc:3: message base_to_car_summary has no signal veh_flag");
}

TEST(FlagCodes, TheDefaultsNameEachFlagAndTheParametersAreChecked) {
  const FlagCodes c;
  EXPECT_EQ(track_flag_for(c, 1), TrackFlag::red);
  EXPECT_EQ(track_flag_for(c, 2), TrackFlag::orange);
  EXPECT_EQ(track_flag_for(c, 3), TrackFlag::yellow);
  EXPECT_EQ(track_flag_for(c, 4), TrackFlag::green);
  EXPECT_EQ(track_flag_for(c, 0), TrackFlag::unknown);
  EXPECT_EQ(track_flag_for(c, 9), TrackFlag::unknown);
  EXPECT_EQ(vehicle_flag_for(c, 0), VehicleFlag::none);
  EXPECT_EQ(vehicle_flag_for(c, 1), VehicleFlag::none);
  EXPECT_EQ(vehicle_flag_for(c, 2), VehicleFlag::black);
  EXPECT_EQ(vehicle_flag_for(c, 4), VehicleFlag::checkered);
  EXPECT_EQ(vehicle_flag_for(c, 8), VehicleFlag::purple);
  EXPECT_EQ(vehicle_flag_for(c, 3), VehicleFlag::unknown);
  for (TrackFlag f : {TrackFlag::red, TrackFlag::orange, TrackFlag::yellow, TrackFlag::green})
    EXPECT_EQ(track_flag_for(c, track_code_of(c, f)), f);
  for (VehicleFlag f : {VehicleFlag::none, VehicleFlag::black, VehicleFlag::checkered, VehicleFlag::purple})
    EXPECT_EQ(vehicle_flag_for(c, vehicle_code_of(c, f)), f);
  std::string param;
  EXPECT_EQ(flag_codes_problem(c, param), "");
  FlagCodes twice = c;
  twice.green = 3;
  EXPECT_EQ(flag_codes_problem(twice, param), "code 3 is 'track_flag_yellow' already");
  EXPECT_EQ(param, "track_flag_green");
  FlagCodes wide = c;
  wide.purple = 16;
  EXPECT_EQ(flag_codes_problem(wide, param), "code 16 does not fit the 4-bit signal (0 to 15)");
  EXPECT_EQ(param, "vehicle_flag_purple");
  FlagCodes zero = c;
  zero.checkered = 0;
  EXPECT_EQ(flag_codes_problem(zero, param), "code 0 reads as no vehicle flag");
  EXPECT_EQ(param, "vehicle_flag_checkered");
}

TEST(RaceControlMonitor, HeardWhileTheHeartbeatMovesLostWhenItStops) {
  RaceControlMonitor m({}, 16);
  EXPECT_EQ(m.check(0), "");  // never heard: nothing to lose
  EXPECT_FALSE(m.state().heard);
  EXPECT_EQ(m.heartbeat_age_s(0), -1);
  RaceSummary s{0, 4, 1, 1, 0, 0, 100};
  EXPECT_EQ(m.received(s, 100 * kMs),
            "race control: track flag NONE -> GREEN (code 4), vehicle flag NONE -> NONE (code 1), target 100 mph");
  EXPECT_EQ(m.check(100 * kMs), "race control heard");
  // At 10 Hz, the heartbeat one more each frame to 9 (at 1.0 s), then 3 (a skip: it moved) and
  // stuck at 3 from 1.2 s: lost once it has not moved for more than 1 s, at 2.2 s.
  for (int k = 1; k <= 21; ++k) {
    s.heartbeat = k < 10 ? k : 3;
    EXPECT_EQ(m.received(s, (100 + 100 * k) * kMs), "");  // the flags did not change
    EXPECT_EQ(m.check((100 + 100 * k) * kMs), k == 21 ? "race control lost: its heartbeat unchanged for 1 s" : "") << k;
  }
  EXPECT_FALSE(m.state().heard);
  EXPECT_EQ(m.state().heartbeat_repeats, 11u);  // frames 11..21 repeated 3
  EXPECT_EQ(m.state().losses, 1u);
  EXPECT_NEAR(m.heartbeat_age_s(2200 * kMs), 1.1, 1e-9);
  s.heartbeat = 9, s.track_code = 3, s.target_mph = 60;  // back, skipping 4..8, and yellow
  EXPECT_EQ(m.received(s, 2300 * kMs),
            "race control: track flag GREEN -> YELLOW (code 3), vehicle flag NONE -> NONE (code 1), target 60 mph");
  EXPECT_EQ(m.check(2300 * kMs), "race control heard");
  EXPECT_EQ(m.state().heartbeat_skips, 2u);  // 9 -> 3 and 3 -> 9
  EXPECT_EQ(m.state().track, TrackFlag::yellow);
  EXPECT_NEAR(m.state().target_speed_mps, 26.8224, 1e-12);
  EXPECT_EQ(m.track_ack(), 3);
  EXPECT_EQ(m.vehicle_ack(), 1);
}

// The car's side reads race control among the reports and loops its codes back in ct_report:
// a yellow (3) with the checkered flag (4): ct_report (1404) = veh_sig_ack 0|8 = 4 in byte 0,
// track_cond_ack 8|16 = 3 in bytes 1..2, ct_state 24|16 = 1 in bytes 3..4, the rolling counter
// 40|8 in byte 5, veh_num 48|8 = 0 in byte 6.
TEST(RaceControl, TheInterfaceReadsTheFlagsAndAcknowledgesThemInCtReport) {
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(car_dbc(), "CAN1-INDY-V14.dbc", error);
  std::optional<DbwMaps> maps = dbw_maps(av21_vehicle(), "av21.json", error);
  RaptorInterface iface(VehicleCanMapping(std::move(*dbc), std::move(*maps)), {}, race_dbc());
  std::vector<CanFrame> acks;
  std::vector<std::string> notes;
  for (int64_t t = 0; t < 300 * kMs; t += 2 * kMs) {
    if (t == 100 * kMs) {
      EXPECT_TRUE(iface.receive({frame(1200, {0x33, 0x04, 0x3C, 0x02, 0, 0, 0, 0})}, t).empty());  // heartbeat 3, yellow, checkered
      EXPECT_EQ(iface.receive({frame(1200, {0x33, 0x04})}, t).front(),
                "base_to_car_summary: frame of 2 bytes, message base_to_car_summary has 8");
    }
    const InterfaceStep s = iface.step(t);
    for (const CanFrame& f : s.frames)
      if (f.id == 1404) acks.push_back(f);
    notes.insert(notes.end(), s.notes.begin(), s.notes.end());
    EXPECT_EQ(s.race_control_changed, t == 100 * kMs) << t;
  }
  ASSERT_EQ(acks.size(), 30u);
  EXPECT_EQ(payload(acks[9]), (std::vector<uint8_t>{0, 0, 0, 1, 0, 9, 0, 0}));  // 90 ms: nothing to acknowledge yet
  EXPECT_EQ(payload(acks[10]), (std::vector<uint8_t>{4, 3, 0, 1, 0, 0, 0, 0}));  // 100 ms: the codes looped back
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0], "race control: track flag NONE -> YELLOW (code 3), vehicle flag NONE -> CHECKERED (code 4), target 60 mph");
  EXPECT_EQ(notes[1], "race control heard");
  EXPECT_EQ(iface.race_control().state().frames, 1u);
  EXPECT_EQ(iface.race_control().state().bad_frames, 1u);
  EXPECT_EQ(iface.counts().other_frames, 0u);
  EXPECT_EQ(iface.race_control().state().last.lap, 2);
}
