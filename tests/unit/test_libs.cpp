// The shared libraries on their own: the vehicle file, one curvature, the track geometry, the
// racing line's speed profile.
#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/curvature.hpp"
#include "track/track.hpp"
#include "vehicle/vehicle.hpp"

#include "av21.hpp"
#include "shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
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
