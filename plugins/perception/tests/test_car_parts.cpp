// A car made whole from the detector's parts (perception/common/car_parts.hpp), called directly:
// detections built as the obstacle detector gives a car: its face towards us and its side's thin
// column stacks, each with its footprint's outline.
#include "perception/common/car_parts.hpp"
#include "perception/common/obstacles.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::perception;

namespace {

const CarShape kCar;  // the AV-21: 4.9 x 1.94 m

// A car centred at (x, y), heading phi (vehicle frame), seen from the sensor at (sensor_x, 0):
// the face turned to it (the back of a car ahead, the front of one behind; its outline the face's
// two ends, its sides' turn the car's) and `stacks` column stacks (a point each, no turn) along the
// side nearer it, `spacing` m apart from that face on.
std::vector<Detection> seen_car(double x, double y, double phi, int stacks, double spacing = 1.2) {
  const double c = std::cos(phi), s = std::sin(phi), ahead = x > kCar.sensor_x ? 1.0 : -1.0;
  const double fx = x - ahead * kCar.length / 2 * c, fy = y - ahead * kCar.length / 2 * s;  // the face's centre
  const double hw = kCar.width / 2;
  const double sides = phi - M_PI / 2 * std::floor(phi / (M_PI / 2));  // the detector's fitted turn, [0, pi/2)
  std::vector<Detection> out{
      {fx, fy, kCar.width * std::abs(s), kCar.width * std::abs(c), {{fx + hw * s, fy - hw * c}, {fx - hw * s, fy + hw * c}}, sides}};
  const double side = y > 0 ? -1.0 : 1.0;  // the side turned to the car's axis
  for (int k = 1; k <= stacks; ++k) {
    const double along = ahead * k * spacing, sx = fx + along * c - side * hw * s, sy = fy + along * s + side * hw * c;
    out.push_back({sx, sy, 0.0, 0.0, {{sx, sy}}, std::nan("")});
  }
  return out;
}

double off(const Detection& d, double x, double y) { return std::hypot(d.x - x, d.y - y); }

}  // namespace

// Ahead, turned 0 to 12 degrees against the track's direction (the prior: the track's heading),
// on either side: one car, at its centre within 5 cm, from its back and its side's stacks.
TEST(CarParts, ACarAheadIsItsBackAndSideMadeWhole) {
  for (double phi_deg : {0.0, 6.0, 12.0, -12.0})
    for (double y : {-3.0, 0.5, 4.0}) {
      const double phi = phi_deg * M_PI / 180;
      const auto parts = seen_car(70, y, phi, 3);
      const auto whole = whole_cars(parts, std::vector<PriorHeading>(parts.size(), {0.0, false}), kCar);
      ASSERT_EQ(whole.size(), 1u) << phi_deg << " deg, y " << y;
      EXPECT_LT(off(whole[0], 70, y), 0.05) << phi_deg << " deg, y " << y << ": at " << whole[0].x << ", " << whole[0].y;
      EXPECT_EQ(whole[0].size_x, kCar.length);
    }
}

// Its back alone, the track's heading known: the centre half a car beyond it.
TEST(CarParts, ABackAloneIsCompletedAlongTheTrack) {
  const double phi = 8 * M_PI / 180;
  const auto parts = seen_car(60, -2, phi, 0);
  const auto whole = whole_cars(parts, {{phi, false}}, kCar);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_LT(off(whole[0], 60, -2), 0.05);
}

// Behind us: its front is seen, and the centre lies half a car behind it.
TEST(CarParts, ACarBehindIsCompletedAwayFromUs) {
  const auto parts = seen_car(-20, 1.5, 0.0, 2);
  const auto whole = whole_cars(parts, std::vector<PriorHeading>(parts.size(), {0.0, false}), kCar);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_LT(off(whole[0], -20, 1.5), 0.05);
}

// Far off, a side's stacks land further apart than join_gap: those within the car's footprint are
// still its, not cars of their own.
TEST(CarParts, FarStacksWithinTheFootprintAreTheCars) {
  const auto parts = seen_car(150, 3, 0.05, 2, 2.3);
  const auto whole = whole_cars(parts, std::vector<PriorHeading>(parts.size(), {0.05, false}), kCar);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_LT(off(whole[0], 150, 3), 0.05);
}

// Side by side 1.5 m apart, or nose to tail 1 m apart: two cars, each at its centre. A pylon
// beside a car stays a pylon, where the detector put it.
TEST(CarParts, TwoCarsAreNeverOneAndAPylonIsLeftAsItIs) {
  auto parts = seen_car(50, 0, 0, 2);
  const auto beside = seen_car(50, 0 + kCar.width + 1.5, 0, 0);
  parts.insert(parts.end(), beside.begin(), beside.end());
  auto whole = whole_cars(parts, std::vector<PriorHeading>(parts.size(), {0.0, false}), kCar);
  ASSERT_EQ(whole.size(), 2u);
  EXPECT_LT(std::min(off(whole[0], 50, 0), off(whole[1], 50, 0)), 0.05);
  EXPECT_LT(std::min(off(whole[0], 50, 3.44), off(whole[1], 50, 3.44)), 0.05);

  parts = seen_car(40, 0, 0, 0);
  const auto behind_it = seen_car(40 + kCar.length + 1.0, 0, 0, 0);
  parts.insert(parts.end(), behind_it.begin(), behind_it.end());
  whole = whole_cars(parts, std::vector<PriorHeading>(parts.size(), {0.0, false}), kCar);
  EXPECT_EQ(whole.size(), 2u);

  const Detection pylon{30, -3, 0.5, 0.5};
  whole = whole_cars({pylon}, {{0.0, false}}, kCar);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].x, pylon.x);
  EXPECT_EQ(whole[0].size_x, pylon.size_x);
}

// The detector's side of it (obstacles.hpp): a car's back and side seen at a slant, as points, an
// L: the rectangle fitted to them is turned as the car is (a quarter turn either way), where its
// hull alone is a triangle; a face alone, turned as the face; the hull counter-clockwise, its
// corners only.
TEST(CarParts, TheDetectorFitsACarsSidesAndItsHull) {
  for (double yaw_deg : {0.0, 20.0, 55.0, -30.0}) {
    const double yaw = yaw_deg * M_PI / 180, c = std::cos(yaw), s = std::sin(yaw);
    Points pts;
    std::vector<int> members;
    for (double a = 0; a <= 1.94; a += 0.1) pts.push_back(Point(40 + a * -s, 5 + a * c, 0.5f)), members.push_back(static_cast<int>(pts.size()) - 1);
    for (double a = 0.1; a <= 3.0; a += 0.15) pts.push_back(Point(40 + a * c, 5 + a * s, 0.5f)), members.push_back(static_cast<int>(pts.size()) - 1);
    const double quarter = M_PI / 2, want = yaw - quarter * std::floor(yaw / quarter);
    const double got = fitted_box_yaw(pts, members);
    EXPECT_NEAR(std::remainder(got - want, quarter), 0.0, 0.2 * M_PI / 180) << yaw_deg << " deg";
    members.resize(20);  // the face alone
    EXPECT_NEAR(std::remainder(fitted_box_yaw(pts, members) - want, quarter), 0.0, 0.2 * M_PI / 180) << yaw_deg << " deg, a face";
  }
  Points square;
  std::vector<int> all;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 2; ++j) square.push_back(Point(i, j, 0)), all.push_back(static_cast<int>(square.size()) - 1);
  const auto hull = footprint_hull(square, all);
  ASSERT_EQ(hull.size(), 4u);
  double area = 0;
  for (std::size_t k = 0; k < hull.size(); ++k) area += hull[k].x() * hull[(k + 1) % 4].y() - hull[(k + 1) % 4].x() * hull[k].y();
  EXPECT_NEAR(area / 2, 8.0, 1e-6) << "counter-clockwise";
  EXPECT_TRUE(std::isnan(fitted_box_yaw(square, {0, 1, 2})));
}
