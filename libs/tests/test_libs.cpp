// The shared libraries on their own: the vehicle file, one curvature, the track geometry, the
// racing line's speed profile.
#include "math/estimate_history.hpp"
#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/curvature.hpp"
#include "track/track.hpp"
#include "vehicle/vehicle.hpp"

#include "cloud/quantized_cloud.hpp"

#include <brickyard/msgs/PointCloud.h>
#include <brickyard/msgs/QuantizedPointCloud.h>

#include "av21.hpp"
#include "shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

using namespace brickyard;

namespace {

std::string av21_text() {
  std::ifstream f(BRICKYARD_SOURCE_DIR "/data/vehicles/av21.json");
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The AV-21's file with one replacement, parsed; the error's text (empty when it parsed).
std::string error_of(const std::string& from, const std::string& to) {
  std::string t = av21_text();
  const auto at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  t.replace(at, from.size(), to);
  try {
    vehicle::parse_vehicle(t, "car.json");
  } catch (const vehicle::VehicleFileError& e) {
    return e.what();
  }
  return "";
}

track::CenterLine circle(double r, int n, double width) { return circle_line<track::CenterLine>(r, n, width); }

}  // namespace

TEST(Vehicle, TheAv21FileHoldsTheCar) {
  const vehicle::Vehicle v = av21_vehicle();
  EXPECT_EQ(v.name, "Dallara AV-21");
  EXPECT_DOUBLE_EQ(v.wheelbase, 2.97);
  EXPECT_NEAR(v.lf + v.lr, v.wheelbase, 1e-12);
  EXPECT_DOUBLE_EQ(v.mass, 815);
  EXPECT_EQ(v.tyre, "linear");
  EXPECT_DOUBLE_EQ(v.mount("gnss_left").xyz[0], 1.606);
  EXPECT_DOUBLE_EQ(v.mount("lidar_left").rpy_deg[2], 120);
  EXPECT_THROW(v.mount("lidar_rear"), vehicle::VehicleFileError);
  ASSERT_TRUE(v.drive_by_wire);
  EXPECT_DOUBLE_EQ(v.drive_by_wire->max_brake_pressure_kpa, 6000);
  EXPECT_DOUBLE_EQ(v.drive_by_wire->tyre_radius, 0.3);
  EXPECT_DOUBLE_EQ(v.drive_by_wire->final_drive, 3.0);
  EXPECT_EQ(v.drive_by_wire->gear_ratios, (std::vector<double>{2.9167, 1.875, 1.3809, 1.1154, 0.96, 0.8889}));
  EXPECT_DOUBLE_EQ(v.drive_by_wire->redline_rpm, 7500);
}

// The drive-by-wire's section is optional (a car only simulated needs none), and read as strictly
// as the rest when it is there.
TEST(Vehicle, TheDriveByWireSectionIsOptionalAndChecked) {
  std::string t = av21_text();
  t.erase(t.find(",\n  \"drive_by_wire\""), t.rfind('}') - t.find(",\n  \"drive_by_wire\""));
  EXPECT_FALSE(vehicle::parse_vehicle(t, "car.json").drive_by_wire);
  EXPECT_EQ(error_of("\"final_drive\": 3.0,", ""), "car.json: /drive_by_wire: missing key \"final_drive\"");
  EXPECT_EQ(error_of("\"final_drive\": 3.0,", "\"final_drive\": 3.0, \"clutch\": 1,"), "car.json: /drive_by_wire/clutch: unknown key");
  EXPECT_EQ(error_of("[2.9167, 1.875,", "[2.9167, 3.1,"), "car.json: /drive_by_wire/gear_ratios/1: each gear's ratio must be below the one before");
  EXPECT_EQ(error_of("[2.9167, 1.875, 1.3809, 1.1154, 0.96, 0.8889]", "[]"), "car.json: /drive_by_wire/gear_ratios: expected 1 to 16 numbers");
  EXPECT_EQ(error_of("[2.9167,", "[-1,"), "car.json: /drive_by_wire/gear_ratios/0: expected a ratio above 0, at most 50");
  EXPECT_EQ(error_of("\"max_brake_pressure_kpa\": 6000", "\"max_brake_pressure_kpa\": 0"),
            "car.json: /drive_by_wire/max_brake_pressure_kpa: expected a number from 1 to 100000, found 0");
}

TEST(Vehicle, BadFilesNameTheFileAndThePointer) {
  EXPECT_EQ(error_of("\"lf_m\": 1.68,", "\"lf_m\": 1.68, \"cg_height_m\": 0.3,"), "car.json: /geometry/cg_height_m: unknown key");
  EXPECT_EQ(error_of("\"lf_m\"", "\"lf\""), "car.json: /geometry: missing key \"lf_m\"");
  EXPECT_EQ(error_of("\"mass_kg\": 815", "\"mass_kg\": -1"), "car.json: /mass/mass_kg: expected a number from 1 to 100000, found -1");
  EXPECT_EQ(error_of("\"model\": \"linear\"", "\"model\": \"slick\""), "car.json: /tyres/model: expected \"linear\" or \"pacejka\", found \"slick\"");
  EXPECT_EQ(error_of("\"lr_m\": 1.29", "\"lr_m\": 1.5"), "car.json: /geometry: lf_m + lr_m must equal wheelbase_m");
  EXPECT_EQ(error_of("\"xyz\": [2.342, 0, 0.448]", "\"xyz\": [2.342, 0]"), "car.json: /mounts/lidar_front/xyz: expected [x, y, z]");
  EXPECT_EQ(error_of("\"aero\"", "\"aerodynamics\""), "car.json: /: missing key \"aero\"");
  // An envelope the car cannot drive: more lateral grip than its tyres, more braking than its brakes.
  EXPECT_EQ(error_of("\"a_lat_mps2\": 15", "\"a_lat_mps2\": 18"),
            "car.json: /limits/a_lat_mps2: 18 m/s^2 is more than the tyres' grip (mu 1.6 x g = 15.70 m/s^2)");
  EXPECT_EQ(error_of("\"max_brake_force_n\": 20000", "\"max_brake_force_n\": 8000"),
            "car.json: /limits/a_decel_mps2: 15 m/s^2 is more than the car can brake (tyres 15.70, brakes 9.82 m/s^2)");
  EXPECT_NE(error_of("{", "["), "");  // not an object at all
  EXPECT_THROW(vehicle::load_vehicle("/no/such/car.json"), vehicle::VehicleFileError);
  // A device where the file should be: refused unread (/dev/zero would grow without end).
  try {
    vehicle::load_vehicle("/dev/zero");
    ADD_FAILURE() << "/dev/zero read as a vehicle";
  } catch (const vehicle::VehicleFileError& e) {
    EXPECT_STREQ(e.what(), "/dev/zero: not a regular file");
  }
}

// The AV-21's limits as the racing-line comparison and brickyard-plan take them.
TEST(Vehicle, SpeedProfileLimitsFollowFromTheCar) {
  const vehicle::Vehicle v = av21_vehicle();
  const motion::VehicleLimits l = motion::vehicle_limits(v);
  EXPECT_DOUBLE_EQ(l.a_accel, 9000.0 / 815);
  EXPECT_DOUBLE_EQ(l.power, 370e3 / 815);
  EXPECT_DOUBLE_EQ(l.drag, 1.2 * 0.85 / (2 * 815));
  EXPECT_DOUBLE_EQ(l.a_lat, 15);
  EXPECT_TRUE(l.ellipse);
}

TEST(Curvature, MengerOfACircleAndOfCoincidentPoints) {
  const double r = 50;
  double sides = 0;
  const double k = track::menger_curvature(r, 0, 0, r, -r, 0, &sides);  // counter-clockwise
  EXPECT_NEAR(k, 1 / r, 1e-12);
  EXPECT_NEAR(sides, 2 * std::sqrt(2.0) * r, 1e-9);
  EXPECT_NEAR(track::menger_curvature(-r, 0, 0, r, r, 0), -1 / r, 1e-12);  // clockwise: negative
  EXPECT_EQ(track::menger_curvature(1, 1, 1, 1, 2, 3), 0);
  const auto ks = track::signed_curvature(circle(r, 400, 5), 0);
  for (double x : ks) EXPECT_NEAR(x, 1 / r, 1e-4);
}

TEST(TrackGeometry, FrenetRoundTripAndEdges) {
  const track::Track t({"ring", circle(100, 400, 6), {}});
  EXPECT_NEAR(t.length(), 2 * M_PI * 100, 0.05);
  EXPECT_TRUE(t.counter_clockwise());
  const track::Frenet f = t.at(123.4, -2.5);
  const Eigen::Vector2d p = t.position(f);
  const track::Frenet g = t.project(p.x(), p.y());
  EXPECT_NEAR(g.s, 123.4, 1e-6);
  EXPECT_NEAR(g.d, -2.5, 1e-6);
  EXPECT_DOUBLE_EQ(t.width_left(g.seg, g.u), 6);
  EXPECT_DOUBLE_EQ(t.road_z(g), 0);  // flat without a bank profile
  EXPECT_THROW(track::Track({"three", circle(100, 3, 6), {}}), std::invalid_argument);
}

// The racing line's profile is the one speed profile with the lateral and longitudinal budgets
// independent: the same numbers, bit for bit, as speed_profile itself.
TEST(RacingLine, ItsProfileIsTheSpeedProfile) {
  track::CenterLine c = circle(200, 300, 8);
  for (std::size_t i = 0; i < c.x.size(); ++i) c.x[i] *= 1.8;  // an oval: straights and turns
  const motion::VehicleLimits lim = motion::independent_limits(60, 15, 8, 12);
  const motion::RacingLine r = motion::make_racing_line(c, lim, 30);
  std::vector<double> ds(c.x.size());
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const std::size_t j = (i + 1) % ds.size();
    ds[i] = std::hypot(c.x[j] - c.x[i], c.y[j] - c.y[i]);
  }
  EXPECT_EQ(r.speed, motion::speed_profile(ds, track::signed_curvature(c, 30), lim, true));
  EXPECT_LT(*std::min_element(r.speed.begin(), r.speed.end()), 60);
  EXPECT_DOUBLE_EQ(*std::max_element(r.speed.begin(), r.speed.end()), 60);
}

TEST(RacingLine, KeepInsidePullsPointsOffTheEdges) {
  const track::Track t({"ring", circle(100, 400, 5), {}});
  track::CenterLine line = circle(104.8, 200, 0);  // 4.8 m left of the centre: 0.2 m from the edge
  const track::CenterLine kept = motion::keep_inside(line, t, 1.0);
  for (std::size_t i = 0; i < kept.x.size(); ++i) EXPECT_NEAR(std::hypot(kept.x[i], kept.y[i]), 104.0, 0.02);
}

// A line on the track passes; one a metre past an edge is named, point and distance.
TEST(RacingLine, LeavesTrackNamesThePoint) {
  const track::Track t({"ring", circle(100, 400, 5), {}});
  EXPECT_EQ(motion::leaves_track(circle(104.8, 200, 0), t), "");
  const std::string e = motion::leaves_track(circle(106, 200, 0), t);
  EXPECT_NE(e.find("point 1 (106.00, 0.00) is 1.00 m beyond the track's right edge"), std::string::npos) << e;
}

// ---- compact clouds for recordings (libs/cloud/quantized_cloud.hpp) ----

TEST(QuantizedCloud, RoundTripWithinHalfThePrecision) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-200.0f, 200.0f), w(0.0f, 0.8f);
  std::vector<float> x(5000), y(5000), z(5000), in(5000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng) / 50, in[i] = w(rng);
  for (double precision : {0.001, 0.01, 0.05}) {
    const auto q = brickyard::cloud::quantize(x, y, z, in, precision);
    std::vector<float> rx, ry, rz, ri;
    brickyard::cloud::restore(q, rx, ry, rz, ri);
    ASSERT_EQ(rx.size(), x.size());
    double worst = 0, worst_i = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      worst = std::max({worst, std::abs(double(rx[i]) - x[i]), std::abs(double(ry[i]) - y[i]), std::abs(double(rz[i]) - z[i])});
      worst_i = std::max(worst_i, std::abs(double(ri[i]) - in[i]));
    }
    EXPECT_LE(worst, precision / 2 + 2e-5) << precision;  // float32 at 200 m holds 15 µm
    EXPECT_LE(worst_i, q.intensity_max / 510.0 + 1e-6);
  }
}

TEST(QuantizedCloud, AScanLineIsSmallStepsAndPointsNotFiniteComeBackAsNaN) {
  // A ring of returns 30 m round, 0.1° apart: each step a few centimetres.
  std::vector<float> x, y, z, in;
  for (int k = 0; k < 3600; ++k) {
    const double a = k * 0.1 * M_PI / 180;
    x.push_back(static_cast<float>(30 * std::cos(a))), y.push_back(static_cast<float>(30 * std::sin(a))), z.push_back(-1.5f), in.push_back(0.2f);
  }
  x[10] = std::numeric_limits<float>::quiet_NaN();
  y[20] = 3e38f;  // beyond 2^31 centimetres
  const auto q = brickyard::cloud::quantize(x, y, z, in, 0.01);
  ASSERT_EQ(q.not_finite, (std::vector<std::uint32_t>{10, 20}));
  // Steps of at most 6 cm a coordinate, zigzag-coded: below 256, so every plane but the low bytes' is zero.
  const std::size_t n = x.size();
  ASSERT_EQ(q.steps.size(), 12 * n);
  for (int axis = 0; axis < 3; ++axis)
    for (int b = 1; b < 4; ++b)
      for (std::size_t i = 1; i < n; ++i) ASSERT_EQ(q.steps[(4 * axis + b) * n + i], 0) << axis << " " << b << " " << i;
  std::vector<float> rx, ry, rz, ri;
  brickyard::cloud::restore(q, rx, ry, rz, ri);
  EXPECT_TRUE(std::isnan(rx[10]) && std::isnan(ry[10]) && std::isnan(rz[10]));
  EXPECT_TRUE(std::isnan(ry[20]));
  EXPECT_NEAR(rx[21], x[21], 0.005 + 1e-5);  // the points after them are where they were
  EXPECT_NEAR(ry[3599], y[3599], 0.005 + 1e-5);
}

TEST(QuantizedCloud, BadInputIsNamed) {
  using brickyard::cloud::quantize;
  const std::vector<float> a{1, 2}, b{1};
  auto error = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error([&] { quantize(a, a, a, {}, 0); }).find("expected (0, 1] m"), std::string::npos);
  EXPECT_EQ(error([&] { quantize(a, b, a, {}, 0.01); }), "x, y, z and intensity hold 2, 1, 2 and 0 values");
  brickyard::cloud::Quantized q = quantize(a, a, a, {}, 0.01);
  q.not_finite = {5};
  std::vector<float> x, y, z, i;
  EXPECT_EQ(error([&] { brickyard::cloud::restore(q, x, y, z, i); }), "not_finite lists point 5 out of order or beyond the cloud's 2");
  q.not_finite.clear();
  q.steps.pop_back();
  EXPECT_EQ(error([&] { brickyard::cloud::restore(q, x, y, z, i); }), "steps hold 23 bytes, not 12 a point");
}

TEST(QuantizedCloud, ThePointCloudMessageComesBackWithItsHeaderAndMount) {
  brickyard::msgs::PointCloud c;
  c.header().stamp_ns(123456789);
  c.header().frame_id("lidar_front");
  c.sensor_id(2);
  c.sensor_x(1.5), c.sensor_yaw(0.25);
  c.x({1.234f, 5.678f}), c.y({-1.0f, 2.0f}), c.z({0.5f, 0.25f}), c.intensity({0.1f, 0.4f});
  c.time_offset({-0.0499f, 0.0312f});
  auto q = brickyard::cloud::pack<brickyard::msgs::PointCloud, brickyard::msgs::QuantizedPointCloud>(c, 0.001);
  const auto r = brickyard::cloud::unpack<brickyard::msgs::PointCloud>(q);
  EXPECT_EQ(r.time_offset(), c.time_offset());  // the points' times as they were
  EXPECT_EQ(r.header().stamp_ns(), 123456789);
  EXPECT_EQ(r.header().frame_id(), "lidar_front");
  EXPECT_EQ(r.sensor_id(), 2);
  EXPECT_EQ(r.sensor_x(), 1.5);
  EXPECT_EQ(r.sensor_yaw(), 0.25);
  ASSERT_EQ(r.x().size(), 2u);
  EXPECT_NEAR(r.x()[1], 5.678f, 0.0005 + 1e-6);
  EXPECT_NEAR(r.intensity()[0], 0.1f, 0.4 / 510 + 1e-6);
  q.time_offset({0.0f});  // a time for one point of two: named, not restored
  EXPECT_THROW(brickyard::cloud::unpack<brickyard::msgs::PointCloud>(q), std::invalid_argument);
}

// The estimate history: bounded, the nearest by stamp (the newest at a tie), the pose at a stamp
// interpolated between the two around it with the heading the short way round across +-pi.
TEST(EstimateHistory, NearestByStampTheNewestAtATie) {
  brickyard::math::EstimateHistory<int> h(8);
  EXPECT_EQ(h.nearest(0), nullptr);
  h.add(100, {0, 0, 0}, 0);
  h.add(200, {1, 0, 0}, 1);
  h.add(300, {2, 0, 0}, 2);
  EXPECT_EQ(h.nearest(190)->estimate, 1);
  EXPECT_EQ(h.nearest(-5)->estimate, 0);
  EXPECT_EQ(h.nearest(250)->estimate, 2);
  EXPECT_EQ(h.nearest(150)->estimate, 0);  // a tie between older ones: the first to arrive
  EXPECT_EQ(h.nearest(INT64_MAX)->estimate, 2);
  EXPECT_EQ(h.nearest(INT64_MIN)->estimate, 0);
}

TEST(EstimateHistory, KeepsTheNewestCapacity) {
  brickyard::math::EstimateHistory<int> h(2);
  for (int i = 0; i < 5; ++i) h.add(i * 10, {double(i), 0, 0}, i);
  EXPECT_EQ(h.size(), 2u);
  EXPECT_EQ(h.newest().estimate, 4);
  EXPECT_EQ(h.nearest(0)->estimate, 3);
  brickyard::math::EstimateHistory<int> one(0);  // at least one
  one.add(0, {}, 7);
  one.add(1, {}, 8);
  EXPECT_EQ(one.size(), 1u);
}

TEST(EstimateHistory, PoseAtInterpolatesBetweenTheTwoAroundTheStamp) {
  brickyard::math::EstimateHistory<int> h(8);
  EXPECT_FALSE(h.at(0));
  h.add(8'000'000, {0.64, 0.08, -3.1}, 2);  // arrived out of order: placed by its stamp
  h.add(0, {0.0, 0.0, 3.1}, 1);
  const auto p = *h.at(2'000'000);
  EXPECT_TRUE(p.interpolated);
  EXPECT_NEAR(p.pose.x, 0.16, 1e-12);
  EXPECT_NEAR(p.pose.y, 0.02, 1e-12);
  EXPECT_NEAR(std::remainder(p.pose.yaw - (3.1 + 0.25 * (2 * M_PI - 6.2)), 2 * M_PI), 0.0, 1e-12);
  EXPECT_EQ(p.nearer->estimate, 1);
  EXPECT_EQ(h.at(6'000'000)->nearer->estimate, 2);
  EXPECT_EQ(h.at(4'000'000)->nearer->estimate, 2);  // a tie: the newer
  const auto late = *h.at(9'000'000);
  EXPECT_FALSE(late.interpolated);
  EXPECT_EQ(late.pose.x, 0.64);
  EXPECT_EQ(h.at(-1)->pose.x, 0.0);
  EXPECT_EQ(h.at(0)->pose.yaw, 3.1);  // on a sample's stamp: that sample
}
