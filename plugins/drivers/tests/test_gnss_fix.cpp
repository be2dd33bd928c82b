// From a receiver's report to the stack's fix: the datum (checked against the ellipsoid's
// meridian and parallel radii, worked out here from WGS84's constants, not from GeographicLib),
// the fix's sigmas, type and time from NovAtel's real BESTPOSA logs (data/gnss), GGA's sigma rule,
// the time rule (device_clock.hpp) on a stream of known delays, and replay pacing.
#include "drivers/common/device_clock.hpp"
#include "drivers/common/gnss_fix_values.hpp"
#include "drivers/common/gnss_report.hpp"
#include "drivers/common/gnss_stream.hpp"
#include "drivers/common/gnss_time.hpp"
#include "drivers/common/latency_spread.hpp"
#include "drivers/common/nmea0183.hpp"
#include "drivers/common/raw_imu.hpp"
#include "drivers/common/replay_pacer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

using namespace brickyard::drivers;

namespace {

std::string read_gnss_file(const char* name) {
  std::ifstream in(std::string(BRICKYARD_SOURCE_DIR) + "/data/gnss/" + name, std::ios::binary);
  EXPECT_TRUE(in.good()) << name;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The first log of novatel_BESTPOS.GPS: 51.11637049360, -114.03827102462, 1059.7447 m above MSL,
// undulation -16.9 m: 1042.8447 m above the ellipsoid.
const Datum kFirstLog{51.11637049360, -114.03827102462, 1059.7447 - 16.9};

constexpr double kA = 6378137.0, kF = 1 / 298.257223563;  // WGS84
constexpr double kE2 = kF * (2 - kF);
constexpr double kDeg = M_PI / 180;

}  // namespace

TEST(LocalDatum, SmallStepsNorthAndEastAreTheEllipsoidsRadiiTimesTheAngle) {
  const LocalDatum d(kFirstLog);
  const Eigen::Vector3d origin = d.to_map({kFirstLog.latitude_deg, kFirstLog.longitude_deg, kFirstLog.height_m});
  EXPECT_NEAR(origin.norm(), 0, 1e-9);
  const double s = std::sin(kFirstLog.latitude_deg * kDeg);
  const double meridian = kA * (1 - kE2) / std::pow(1 - kE2 * s * s, 1.5) + kFirstLog.height_m;  // m per rad north
  const double parallel = (kA / std::sqrt(1 - kE2 * s * s) + kFirstLog.height_m) * std::cos(kFirstLog.latitude_deg * kDeg);
  const double step = 1e-4;  // deg: 11 m north, 7 m east; the curvature's share is under 0.01 mm
  const Eigen::Vector3d north = d.to_map({kFirstLog.latitude_deg + step, kFirstLog.longitude_deg, kFirstLog.height_m});
  const Eigen::Vector3d east = d.to_map({kFirstLog.latitude_deg, kFirstLog.longitude_deg + step, kFirstLog.height_m});
  EXPECT_NEAR(north.y(), meridian * step * kDeg, 1e-4);
  EXPECT_NEAR(north.x(), 0, 1e-6);
  EXPECT_NEAR(east.x(), parallel * step * kDeg, 1e-4);
  EXPECT_NEAR(east.y(), 0, 1e-4);
  const Eigen::Vector3d up = d.to_map({kFirstLog.latitude_deg, kFirstLog.longitude_deg, kFirstLog.height_m + 10});
  EXPECT_NEAR(up.z(), 10, 1e-6);
  const Geodetic back = d.to_geodetic(Eigen::Vector3d(1234.5, -678.9, 12.3));
  EXPECT_NEAR((d.to_map(back) - Eigen::Vector3d(1234.5, -678.9, 12.3)).norm(), 0, 1e-6);
  EXPECT_STREQ(datum_problem(kFirstLog), "");
  EXPECT_STRNE(datum_problem({91, 0, 0}), "");
  EXPECT_STRNE(datum_problem({0, NAN, 0}), "");
}

TEST(GnssFix, TheRealBestposLogsBecomeFixesWithTheirSigmasTypeAndGpsTime) {
  GnssStream stream({GnssProtocol::novatel_oem7, Oem7PositionLog::bestpos, kFirstLog, {}, {}});
  stream.feed(read_gnss_file("novatel_BESTPOS.GPS"));
  stream.finish();
  std::vector<GnssFixValues> fixes;
  while (auto f = stream.next()) fixes.push_back(*f);
  ASSERT_EQ(fixes.size(), 1000u);
  EXPECT_EQ(stream.counters().fixes, 1000u);
  EXPECT_EQ(stream.counters().unusable + stream.counters().other_datum + stream.counters().other_reports, 0u);
  const GnssFixValues& f = fixes.front();
  EXPECT_NEAR(std::hypot(f.x, f.y, f.z), 0, 1e-6);
  EXPECT_FLOAT_EQ(f.sigma_x, 1.5644f);  // east: the longitude's sigma
  EXPECT_FLOAT_EQ(f.sigma_y, 1.8736f);  // north: the latitude's
  EXPECT_FLOAT_EQ(f.sigma_z, 2.8763f);
  EXPECT_EQ(f.fix_type, 1);  // SINGLE
  EXPECT_TRUE(f.valid);
  ASSERT_TRUE(f.device_time_ns);
  EXPECT_EQ(*f.device_time_ns, (1984 * 604800 + 450849) * int64_t{1000000000} + 500000000);
  // A receiver standing still, single-point: every fix within a few of its sigmas of the first.
  for (const GnssFixValues& g : fixes) EXPECT_LT(std::hypot(g.x, g.y), 30.0);
}

TEST(GnssFix, FixTypesAndValidityFollowTheSolution) {
  const LocalDatum d(kFirstLog);
  BestPos p;
  p.latitude_deg = kFirstLog.latitude_deg, p.longitude_deg = kFirstLog.longitude_deg;
  p.solution_status = SolutionStatus::computed;
  const std::pair<PositionType, int> types[] = {{PositionType::narrow_int, 3}, {PositionType::ins_rtkfixed, 3},
                                                {PositionType::narrow_float, 2}, {PositionType::l1_float, 2},
                                                {PositionType::psrdiff, 1}, {PositionType::ppp, 1}};
  for (const auto& [type, expected] : types) {
    p.position_type = type;
    EXPECT_EQ(fix_from(p, d)->fix_type, expected) << static_cast<int>(type);
  }
  p.solution_status = SolutionStatus::insufficient_obs;
  EXPECT_FALSE(fix_from(p, d)->valid);
  EXPECT_EQ(fix_from(p, d)->fix_type, 0);
  p.header.time_status = TimeStatus::coarse;  // a coarse time is no measurement time
  EXPECT_FALSE(fix_from(p, d)->device_time_ns);
  p.datum_id = kDatumUser;
  EXPECT_FALSE(fix_from(p, d));
  p.datum_id = kDatumWgs84, p.latitude_deg = NAN;
  EXPECT_FALSE(fix_from(p, d));
}

TEST(GnssFix, GgaSigmaIsHdopTimesTheQualitysErrorAndItsTimeTheTimeOfDay) {
  const LocalDatum d({44.068843333, -121.314191667, 1127.7 - 19.6});
  NmeaGga g;
  g.latitude_deg = 44.068843333, g.longitude_deg = -121.314191667;
  g.altitude_msl_m = 1127.7, g.undulation_m = -19.6, g.hdop = 0.98, g.quality = 4;
  g.utc = NmeaTime{20, 26, 40.5};
  auto f = fix_from(g, d);
  ASSERT_TRUE(f);
  EXPECT_NEAR(std::hypot(f->x, f->y, f->z), 0, 1e-6);
  EXPECT_EQ(f->fix_type, 3);
  EXPECT_DOUBLE_EQ(f->sigma_x, 0.98 * 0.02);
  EXPECT_DOUBLE_EQ(f->sigma_z, 2 * 0.98 * 0.02);
  EXPECT_EQ(*f->device_time_ns, (20 * 3600 + 26 * 60 + 40) * int64_t{1000000000} + 500000000);
  g.quality = 2;
  EXPECT_DOUBLE_EQ(fix_from(g, d)->sigma_y, 0.98 * 0.7);
  g.quality = 8;  // simulator mode: no fix
  EXPECT_FALSE(fix_from(g, d)->valid);
  g.hdop.reset();
  EXPECT_FALSE(fix_from(g, d));
}

namespace {
NmeaTime utc_of(double day_s) {
  const int h = static_cast<int>(day_s / 3600), m = static_cast<int>((day_s - h * 3600) / 60);
  return NmeaTime{h, m, day_s - h * 3600 - m * 60};
}
NmeaGga gga_at(double day_s, int quality) {
  NmeaGga g;
  g.latitude_deg = 44.068843333, g.longitude_deg = -121.314191667;
  g.altitude_msl_m = 1127.7, g.undulation_m = -19.6, g.hdop = 0.98, g.quality = quality;
  g.utc = utc_of(day_s);
  return g;
}
NmeaGst gst_at(double day_s) {
  NmeaGst g;
  g.utc = utc_of(day_s);
  g.latitude_sigma_m = 0.023, g.longitude_sigma_m = 0.020, g.height_sigma_m = 0.031;
  return g;
}
}  // namespace

// A receiver's GST gives its GGA fixes their sigmas: one of the GGA's own time (sent before it),
// or of the epoch before (sent after that epoch's GGA, as most receivers do) while the fix type
// holds; not across a change of solution, nor from two epochs back, nor past max_age_s.
TEST(GnssFix, GgaSigmasFromTheReceiversGstOfItsEpochOrTheOneBefore) {
  const LocalDatum d({44.068843333, -121.314191667, 1127.7 - 19.6});
  GstSigmas gst;
  bool from_gst = false;
  auto fix = [&](const NmeaGga& g) {
    GnssFixValues f = *fix_from(g, d);
    from_gst = gst.apply(g, f);
    return f;
  };
  GnssFixValues f = fix(gga_at(1000.0, 4));
  EXPECT_FALSE(from_gst);  // no GST yet: HDOP's rule
  EXPECT_DOUBLE_EQ(f.sigma_x, 0.98 * 0.02);
  gst.gst(gst_at(1000.0));  // after its GGA
  f = fix(gga_at(1000.1, 4));
  EXPECT_TRUE(from_gst);  // the epoch before's, the same fix type
  EXPECT_DOUBLE_EQ(f.sigma_x, 0.020);  // east: the longitude's
  EXPECT_DOUBLE_EQ(f.sigma_y, 0.023);  // north: the latitude's
  EXPECT_DOUBLE_EQ(f.sigma_z, 0.031);
  fix(gga_at(1000.2, 4));
  EXPECT_FALSE(from_gst);  // two epochs back
  gst.gst(gst_at(1000.2));
  f = fix(gga_at(1000.3, 5));
  EXPECT_FALSE(from_gst);  // RTK fixed -> float: the GST was the fixed solution's
  EXPECT_DOUBLE_EQ(f.sigma_x, 0.98 * 0.2);
  gst.gst(gst_at(1000.4));  // before its GGA
  fix(gga_at(1000.4, 5));
  EXPECT_TRUE(from_gst);  // its own epoch's
  gst.gst(gst_at(86399.9));
  fix(gga_at(86399.9, 5));
  fix(gga_at(0.0, 5));
  EXPECT_TRUE(from_gst);  // across midnight: the epoch before, 0.1 s earlier
  gst.gst(gst_at(0.0));
  fix(gga_at(2.0, 5));
  EXPECT_FALSE(from_gst);  // 2 s old, past max_age_s
  NmeaGst no_height = gst_at(2.0);
  no_height.height_sigma_m.reset();
  gst.gst(no_height);  // not kept: a sigma missing
  fix(gga_at(2.0, 5));
  EXPECT_FALSE(from_gst);
}

// Through the stream, as a receiver sends them (GGA, then the epoch's GST): the first GGA takes
// HDOP's rule, the next its epoch-before's GST, counted.
TEST(GnssStream, NmeaFixesTakeTheirSigmasFromTheReceiversGst) {
  GnssStreamParams p;
  p.protocol = GnssProtocol::nmea0183;
  p.datum = {44.068843333, -121.314191667, 1127.7 - 19.6};
  GnssStream s(p);
  const std::string bytes = seal_nmea("GPGGA,202640.000,4404.1306,N,12118.8515,W,2,10,0.98,1127.7,M,-19.6,M,0000,0000") +
                            seal_nmea("GPGST,202640.000,1.8,,,,1.7,1.3,2.2") +
                            seal_nmea("GPGGA,202641.000,4404.1306,N,12118.8515,W,2,10,0.98,1127.7,M,-19.6,M,0000,0000");
  s.feed(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  const std::optional<GnssFixValues> first = s.next(), second = s.next();
  ASSERT_TRUE(first && second);
  EXPECT_DOUBLE_EQ(first->sigma_x, 0.98 * 0.7);  // differential, no GST yet
  EXPECT_DOUBLE_EQ(second->sigma_x, 1.3);
  EXPECT_DOUBLE_EQ(second->sigma_y, 1.7);
  EXPECT_DOUBLE_EQ(second->sigma_z, 2.2);
  EXPECT_EQ(s.counters().gst_sigmas, 1u);
  EXPECT_EQ(s.counters().other_reports, 0u);
}

TEST(DeviceClock, StampsCarryTheLeastDelaySeenNeverMoreThanTheReceiveTime) {
  // A receiver at 20 Hz whose clock is 1.4e9 s ahead of the run's; each log delayed 2 to 30 ms
  // on the wire (whole microseconds), one in ten by exactly 2 ms: every stamp but the first lands
  // exactly 2 ms after its measurement (the least delay is the rule's error), none after receipt.
  DeviceClock clock;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int64_t> late_us(2000, 30000);
  const int64_t ahead = int64_t{1400000000} * 1000000000;
  for (int k = 0; k < 400; ++k) {
    const int64_t measured = (10000 + 50 * k) * int64_t{1000000};  // run clock, ns
    const int64_t delay = (k % 10 == 0 ? 2000 : late_us(rng)) * 1000;
    const int64_t stamp = clock.stamp_ns(measured + ahead, measured + delay);
    EXPECT_LE(stamp, measured + delay);
    if (k > 0) {
      EXPECT_EQ(stamp, measured + 2000000) << k;
    }
  }
  EXPECT_EQ(clock.restarts(), 0u);
  // The receiver's time steps back a day (NMEA's midnight): the estimate starts again.
  const int64_t receive = int64_t{30} * 1000000000;
  EXPECT_EQ(clock.stamp_ns(receive - 10000000 + ahead - int64_t{86400} * 1000000000, receive), receive);
  EXPECT_EQ(clock.restarts(), 1u);
}

TEST(ReplayPacer, RecordsFallDueAtTheirRecordedSpacingOverTheRate) {
  ReplayPacer twice(2.0);
  EXPECT_TRUE(twice.due(1000.0, 5'000'000'000));      // the first: at once
  EXPECT_FALSE(twice.due(1001.0, 5'400'000'000));     // 1 s later in the recording: 0.5 s later in the run
  EXPECT_TRUE(twice.due(1001.0, 5'500'000'000));
  ReplayPacer all(0);
  EXPECT_TRUE(all.due(1.0, 0));
  EXPECT_TRUE(all.due(1e6, 0));
}

TEST(GnssReport, AFixSentAsBestposbIsReadBackAsTheSameFix) {
  // The simulator's side of the wire and the driver's, end to end through the binary log's bytes.
  const Datum datum{39.7930, -86.2389, 220.0};  // near Indianapolis
  const LocalDatum d(datum);
  GnssStream stream({GnssProtocol::novatel_oem7, Oem7PositionLog::bestpos, datum, {}, {}});
  const double x[] = {0.0, 812.345, -1504.25, 2999.999};
  for (int k = 0; k < 4; ++k) {
    GnssFixValues f;
    f.x = x[k], f.y = -0.5 * x[k] + 3.25, f.z = 1.5 + 0.001 * k;
    f.sigma_x = 0.02, f.sigma_y = 0.03, f.sigma_z = 0.05;
    f.fix_type = static_cast<uint8_t>(k);
    f.valid = k > 0;
    const GpsTime t{2400, 1234.05 + 0.05 * k};
    const std::vector<uint8_t> bytes = encode_oem7_binary(bestpos_of(f, d, t));
    stream.feed(bytes.data(), bytes.size());
    const auto back = stream.next();
    ASSERT_TRUE(back) << k;
    EXPECT_NEAR(back->x, f.x, 1e-6);
    EXPECT_NEAR(back->y, f.y, 1e-6);
    EXPECT_NEAR(back->z, f.z, 1e-6);
    EXPECT_FLOAT_EQ(back->sigma_x, 0.02f);
    EXPECT_FLOAT_EQ(back->sigma_y, 0.03f);
    EXPECT_FLOAT_EQ(back->sigma_z, 0.05f);
    EXPECT_EQ(back->fix_type, k);
    EXPECT_EQ(back->valid, k > 0);
    EXPECT_EQ(*back->device_time_ns, (2400 * 604800 + 1234) * int64_t{1000000000} + (50 + 50 * k) * int64_t{1000000});
  }
  EXPECT_EQ(stream.decoder().refused(), 0u);
}

// The simulated car's state to a receiver's motion: 50 m/s heading north-west with 10 m/s
// sideways (left), pitched nose down by its state's convention, nose up by the receiver's.
TEST(GnssReport, ACarsStateIsTheReceiversMotion) {
  const double yaw = 0.75 * M_PI;  // north-west
  const MotionValues m = motion_of_car(50, 10, yaw, 0.02, 0.03);
  EXPECT_NEAR(m.east_mps, 50 * std::cos(yaw) - 10 * std::sin(yaw), 1e-12);  // left of north-west is south-west
  EXPECT_NEAR(m.north_mps, 50 * std::sin(yaw) + 10 * std::cos(yaw), 1e-12);
  EXPECT_LT(m.east_mps, -40);
  EXPECT_EQ(m.up_mps, 0);
  EXPECT_EQ(m.roll, 0.02);
  EXPECT_EQ(m.pitch, -0.03);
  EXPECT_EQ(m.yaw, yaw);
}

// BESTVEL and INSPVAX as the simulator sends them beside BESTPOS: decoded field for field, the
// INSPVAX read back as the same fix by a driver reading INSPVAX, the BESTVEL's direction
// clockwise from north.
TEST(GnssReport, BestvelAndInspvaxSentAreReadBack) {
  const Datum datum{39.7930, -86.2389, 220.0};
  const LocalDatum d(datum);
  GnssFixValues f;
  f.x = 812.5, f.y = -340.25, f.z = 1.5;
  f.sigma_x = 0.02, f.sigma_y = 0.03, f.sigma_z = 0.05;
  f.fix_type = 3, f.valid = true;
  MotionValues m;
  m.east_mps = -30, m.north_mps = 40, m.up_mps = 0.5;  // 50 m/s toward north-west
  m.roll = 0.02, m.pitch = -0.01, m.yaw = std::atan2(40.0, -30.0);
  const GpsTime t{2400, 1234.05};
  NovatelOem7Decoder decoder;
  const std::vector<uint8_t> vel = encode_oem7_binary(bestvel_of(f, m, t));
  decoder.feed(vel.data(), vel.size());
  const auto v = decoder.next();
  ASSERT_TRUE(v && std::holds_alternative<BestVel>(*v));
  const BestVel& bv = std::get<BestVel>(*v);
  EXPECT_DOUBLE_EQ(bv.horizontal_speed_mps, 50);
  EXPECT_NEAR(bv.track_over_ground_deg, 360 - std::atan2(30.0, 40.0) * 180 / M_PI, 1e-9);  // 323.13 deg: north-west
  EXPECT_DOUBLE_EQ(bv.vertical_speed_mps, 0.5);
  EXPECT_EQ(bv.velocity_type, PositionType::narrow_int);
  const InsPvaX sent = inspvax_of(f, m, d, t);
  const std::vector<uint8_t> sent_bytes = encode_oem7_binary(sent);
  decoder.feed(sent_bytes.data(), sent_bytes.size());
  const auto decoded = decoder.next();
  ASSERT_TRUE(decoded && std::holds_alternative<InsPvaX>(*decoded));
  const InsPvaX& iv = std::get<InsPvaX>(*decoded);
  EXPECT_NEAR(iv.azimuth_deg, bv.track_over_ground_deg, 1e-9);  // heading along the motion here
  EXPECT_NEAR(iv.roll_deg, 0.02 * 180 / M_PI, 1e-9);
  EXPECT_NEAR(iv.pitch_deg, -0.01 * 180 / M_PI, 1e-9);
  EXPECT_DOUBLE_EQ(iv.north_velocity_mps, 40);
  EXPECT_DOUBLE_EQ(iv.east_velocity_mps, -30);
  EXPECT_DOUBLE_EQ(iv.up_velocity_mps, 0.5);
  EXPECT_EQ(iv.ins_status, InsStatus::solution_good);
  EXPECT_EQ(sent.position_type, PositionType::ins_rtkfixed);
  GnssStream stream({GnssProtocol::novatel_oem7, Oem7PositionLog::inspvax, datum, {}, {}});
  const std::vector<uint8_t> ins = encode_oem7_binary(sent);
  stream.feed(ins.data(), ins.size());
  const auto back = stream.next();
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->x, f.x, 1e-6);
  EXPECT_NEAR(back->y, f.y, 1e-6);
  EXPECT_NEAR(back->z, f.z, 1e-6);
  EXPECT_EQ(back->fix_type, 3);
  EXPECT_TRUE(back->valid);
  EXPECT_FLOAT_EQ(back->sigma_x, 0.02f);
  f.valid = false;  // no solution: INS inactive, read back invalid
  const std::vector<uint8_t> none = encode_oem7_binary(inspvax_of(f, m, d, t));
  stream.feed(none.data(), none.size());
  const auto invalid = stream.next();
  ASSERT_TRUE(invalid);
  EXPECT_FALSE(invalid->valid);
}

TEST(RawImu, ASampleSentAsRawimusxIsReadBackInTheVehicleFrameToItsQuantum) {
  // An IMU mounted turned 90 deg (its x along the car's y), its Y axis sent negated on the wire.
  RawImuScale scale{1e-7, 1e-9, 125, imu_mount(0, 0, 90)};
  ImuValues v;
  v.accel = {3.5, -12.25, 9.81};
  v.gyro = {0.01, -0.2, 0.75};
  v.device_time_ns = (2400 * int64_t{604800} + 77) * 1000000000 + 8000000;
  const RawImuSX raw = raw_imu_of(v, scale, 41);
  // In the IMU's axes the car's x is the IMU's -y: sent negated, a positive count.
  EXPECT_EQ(raw.accel_minus_y_counts, std::llround(3.5 / (1e-7 * 125)));
  EXPECT_EQ(raw.accel_x_counts, std::llround(-12.25 / (1e-7 * 125)));
  GnssStream stream({GnssProtocol::novatel_oem7, Oem7PositionLog::bestpos, kFirstLog, {}, scale});
  const std::vector<uint8_t> bytes = encode_oem7_binary(raw);
  stream.feed(bytes.data(), bytes.size());
  const auto back = stream.next_imu();
  ASSERT_TRUE(back);
  EXPECT_LT((back->accel - v.accel).norm(), 1e-7 * 125);  // a count's worth
  EXPECT_LT((back->gyro - v.gyro).norm(), 1e-9 * 125);
  EXPECT_EQ(back->device_time_ns, v.device_time_ns);
  EXPECT_EQ(stream.counters().imu_samples, 1u);
  // Without a scale the sample is counted and dropped.
  GnssStream unscaled({GnssProtocol::novatel_oem7, Oem7PositionLog::bestpos, kFirstLog, {}, {}});
  unscaled.feed(bytes.data(), bytes.size());
  EXPECT_FALSE(unscaled.next_imu());
  EXPECT_EQ(unscaled.counters().imu_unscaled, 1u);
}

// A driver's wire-to-message latency: quantiles never under the truth and at most 1 % over it,
// across six decades, the largest exact, messages without an arrival not counted.
TEST(LatencySpread, QuantilesWithinOnePercentAboveAndTheLargestExact) {
  LatencySpread spread;
  std::vector<double> truth;
  std::mt19937 rng(7);
  std::lognormal_distribution<double> delay(std::log(3e-4), 2.0);  // 10 µs to 10 s
  for (int i = 0; i < 20000; ++i) {
    const double s = std::min(900.0, delay(rng));
    const int64_t arrival = int64_t{1} << 40;
    spread.add(arrival + static_cast<int64_t>(std::llround(s * 1e9)), arrival);
    truth.push_back(std::llround(s * 1e9) * 1e-9);
  }
  spread.add(5, -1);  // no arrival known
  EXPECT_EQ(spread.count(), 20000u);
  std::sort(truth.begin(), truth.end());
  for (double q : {0.0, 0.5, 0.9, 0.99, 0.999}) {
    const double exact = truth[static_cast<size_t>(q * (truth.size() - 1))];
    EXPECT_GE(spread.quantile_s(q), exact * (1 - 1e-12)) << q;
    EXPECT_LE(spread.quantile_s(q), std::max(exact * 1.01, 1e-6)) << q;
  }
  EXPECT_DOUBLE_EQ(spread.max_s(), truth.back());
  EXPECT_DOUBLE_EQ(spread.quantile_s(1.0), truth.back());
}
