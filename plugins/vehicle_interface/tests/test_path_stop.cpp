// The stop along the last path (common/path_stop.hpp): when it starts, how it brakes, and that it
// keeps a car on a turn the held wheel would leave. The car here is the linear single-track model
// stepped by the test itself at 1 kHz, the wheel reaching the command after the AV-21's delay.
#include "vehicle_interface/common/path_stop.hpp"
#include "vehicle_interface/common/raptor_interface.hpp"

#include "av21.hpp"
#include "control/vehicle_tracking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>

using namespace brickyard;
using namespace brickyard::vehicle_interface;

namespace {

control::TrackerParams stop_tracker() {
  control::TrackerParams t;
  t.steer_law = control::SteerLaw::lqr;
  t.lqr.r_steer = 200;
  t.command_latency = 0.01;
  control::apply_vehicle(t, av21_vehicle());
  return t;
}

// A turn to the left of `radius` from (0, 0) heading along +x, then straight on: `length` m in all,
// at `speed` each point.
std::vector<control::PathPoint> turn(double radius, double arc, double length, double speed) {
  std::vector<control::PathPoint> pts;
  for (double s = 0; s <= length; s += 2) {
    const double a = std::min(s, arc) / radius;
    double x = radius * std::sin(a), y = radius * (1 - std::cos(a));
    if (s > arc) x += (s - arc) * std::cos(a), y += (s - arc) * std::sin(a);
    pts.push_back({x, y, speed});
  }
  return pts;
}

// The linear single-track car (base_link pose, centre of gravity's lateral speed, yaw rate).
struct TestCar {
  control::LateralModel m;
  double x = 0, y = 0, yaw = 0, v = 0, vy = 0, r = 0, delta = 0;
  std::deque<double> wheel;  // commands on their way to the wheel, one a millisecond

  void step(double dt, double command, double decel) {
    wheel.push_back(command);
    if (wheel.size() > 20) delta = wheel.front(), wheel.pop_front();  // the AV-21's 0.02 s
    const double ff = m.cornering_front * (delta - (vy + m.lf * r) / v), fr = -m.cornering_rear * (vy - m.lr * r) / v;
    vy += dt * ((ff + fr) / m.mass - v * r);
    r += dt * (m.lf * ff - m.lr * fr) / m.yaw_inertia;
    const double side = vy - m.lr * r;
    x += dt * (v * std::cos(yaw) - side * std::sin(yaw));
    y += dt * (v * std::sin(yaw) + side * std::cos(yaw));
    yaw += dt * r;
    v = std::max(3.0, v - decel * dt);  // (the model needs speed; the tests end before a stand)
  }
};

// The distance of (x, y) from the path's polyline.
double off_path(const std::vector<control::PathPoint>& p, double x, double y) {
  double best = 1e300;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double ax = p[i].x - p[i - 1].x, ay = p[i].y - p[i - 1].y, l2 = ax * ax + ay * ay;
    const double u = std::clamp(((x - p[i - 1].x) * ax + (y - p[i - 1].y) * ay) / l2, 0.0, 1.0);
    best = std::min(best, std::hypot(x - p[i - 1].x - u * ax, y - p[i - 1].y - u * ay));
  }
  return best;
}

}  // namespace

TEST(PathStop, BeginsOnlyFromAFreshPathAndEstimate) {
  PathStop stop(stop_tracker(), {});
  EXPECT_FALSE(stop.begin(1.0));  // nothing yet
  stop.estimate({0, 0, 0, 30, 0, 0, 0.95});
  EXPECT_FALSE(stop.begin(1.0));  // no path
  stop.path(0.9, turn(200, 100, 300, 30));
  EXPECT_TRUE(stop.begin(1.0));
  EXPECT_NEAR(stop.pose().x, 1.5, 1e-9);  // carried on from 0.95 s at 30 m/s
  EXPECT_FALSE(stop.begin(1.6));          // the estimate 0.65 s old: more than 0.5 s
  stop.estimate({0, 0, 0, 30, 0, 0, 1.55});
  EXPECT_TRUE(stop.begin(1.6));
  EXPECT_FALSE(stop.begin(3.0));  // the path 2.1 s old
}

TEST(PathStop, BrakesForTheSpeedsAheadAndStandsBeforeTheEnd) {
  PathStopParams p;
  p.decel_mps2 = 5;  // below the watchdog's 6
  PathStop stop(stop_tracker(), p);
  std::vector<control::PathPoint> straight = turn(1e9, 0, 400, 60);
  for (std::size_t i = 0; i < straight.size(); ++i)
    if (straight[i].x >= 100) straight[i].speed = 40;  // a turn's speed 100 m on
  stop.path(0, straight);
  stop.estimate({0, 0, 0, 60, 0, 0, 0});
  ASSERT_TRUE(stop.begin(0));
  // (60^2 - 40^2) / (2 x 100) = 10 m/s^2 for the turn; v^2 / (2 (400 - 40)) = 5 for the end.
  EXPECT_NEAR(stop.step(0, 60, 0, 6).decel, 10, 0.15);
  EXPECT_NEAR(stop.step(0, 30, 0, 6).decel, 6, 1e-9);  // slow enough for both: the watchdog's
  PathStop short_path(stop_tracker(), p);
  short_path.path(0, turn(1e9, 0, 140, 40));
  short_path.estimate({0, 0, 0, 40, 0, 0, 0});
  ASSERT_TRUE(short_path.begin(0));
  EXPECT_NEAR(short_path.step(0, 40, 0, 6).decel, 40.0 * 40 / (2 * (140 - p.end_margin_m)), 0.1);
  EXPECT_NEAR(short_path.step(0, 80, 0, 6).decel, p.max_decel_mps2, 1e-9);
}

TEST(PathStop, BrakesNoHarderThanTheTurnLeaves) {
  const control::TrackerParams t = stop_tracker();
  PathStop stop(t, {});
  std::vector<control::PathPoint> bend = turn(100, 300, 320, 0);  // speeds 0: stand at once, were there grip
  stop.path(0, bend);
  const double a = 0.5;  // 50 m into the turn
  stop.estimate({100 * std::sin(a), 100 * (1 - std::cos(a)), a, 35, 35.0 / 100, 0, 0});
  ASSERT_TRUE(stop.begin(0));
  const StopCommand c = stop.step(0.01, 35, 0.05, 6);
  const double lateral = 35.0 * 35 / 100;  // 12.25 m/s^2 of the AV-21's 15
  EXPECT_NEAR(c.decel, std::sqrt(t.grip * t.grip - lateral * lateral), 0.2);
}

// From a car on the turn at 50 m/s: the stop along the path keeps it within a metre of the path
// for the 150 m of the turn it brakes through; the wheel held at the entry's angle leaves it.
TEST(PathStop, KeepsTheCarOnATurnTheHeldWheelLeaves) {
  const control::TrackerParams t = stop_tracker();
  const std::vector<control::PathPoint> path = turn(250, 150, 400, 50);
  for (bool along : {true, false}) {
    PathStop stop(t, {});
    TestCar car{t.car};
    car.v = 50;
    car.delta = control::steady_steer(t.car, 0, 50);  // straight at the start: the turn starts here
    stop.path(0, path);
    stop.estimate({0, 0, 0, 50, 0, 0, 0});
    ASSERT_TRUE(stop.begin(0));
    double worst = 0;
    for (int k = 1; k <= 3000; ++k) {  // 3 s, some 120 m
      const double now = k * 1e-3;
      const StopCommand c = stop.step(now, car.v, car.delta, 6);
      car.step(1e-3, along ? c.steer : 0.0, 6);
      worst = std::max(worst, off_path(path, car.x, car.y));
    }
    if (along) {
      EXPECT_LT(worst, 1.0);
      EXPECT_LT(std::hypot(stop.pose().x - car.x, stop.pose().y - car.y), 0.05);  // the same model: dead reckoning holds
    } else {
      EXPECT_GT(worst, 10.0);
    }
  }
}

// In the interface: commands stop on a turn; with the stop along the path its steering frames
// carry the turn's angle (the held wheel's are straight), and the stop is counted.
TEST(PathStop, TheInterfaceSteersItsStopAlongThePath) {
  static const DbcReadResult read = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  std::string error;
  for (bool along : {true, false}) {
    std::optional<RaptorDbc> dbc = RaptorDbc::make(*read.database, "CAN1-INDY-V14.dbc", error);
    std::optional<DbwMaps> maps = dbw_maps(av21_vehicle(), "av21.json", error);
    const VehicleCanMapping map(std::move(*dbc), std::move(*maps));
    RaptorInterface iface(map, {});
    if (along) iface.stop_on_path(PathStop(stop_tracker(), {}));
    const std::vector<control::PathPoint> path = turn(200, 400, 400, 30);
    DbwSetpoint sent;  // the commands read back as the drive-by-wire reads them
    uint32_t n = 0;
    for (int64_t t = 0; t < 2000 * 1'000'000LL; t += 2'000'000) {
      const double now = static_cast<double>(t) * 1e-9;
      if (t < 1000 * 1'000'000LL && t % 10'000'000 == 0) iface.command({0.0, 0.3, 0, 30});
      if (PathStop* s = iface.path_stop(); s && t % 10'000'000 == 0) s->path(now, path), s->estimate({0, 0, 0, 30, 0, 0, now});
      if (t % 10'000'000 == 0) {
        DbwReports r;
        r.wheel_fl = r.wheel_fr = r.wheel_rl = r.wheel_rr = r.speed = 30;
        std::vector<CanFrame> frames;
        for (RaptorMessage m : kRaptorReports) frames.push_back(map.report_frame(m, r, n).frame);
        ++n;
        iface.receive(frames, t);
      }
      for (const CanFrame& f : iface.step(t).frames) map.read_command(f, sent);
    }
    EXPECT_EQ(iface.counts().path_stops, along ? 1u : 0u);
    EXPECT_EQ(iface.counts().held_stops, along ? 0u : 1u);
    // A 200 m turn: about atan(2.97 / 200) of road wheel, 15 times that at the motor (12.8 deg).
    if (along) EXPECT_GT(sent.actuation.steer_motor_deg, 8.0);
    else EXPECT_EQ(sent.actuation.steer_motor_deg, 0.0);
  }
}

// Front tyres a fifth softer than the vehicle file says (worn, cold): the car turns less than the
// model says for its wheel. The IMU's yaw rate, fed to the stop, keeps its dead reckoning on the
// car; without it the reckoning drifts off by metres.
TEST(PathStop, TurnsByTheGyroWhereTheModelIsWrong) {
  const control::TrackerParams t = stop_tracker();
  const std::vector<control::PathPoint> path = turn(300, 400, 400, 50);
  for (bool gyro : {true, false}) {
    PathStop stop(t, {});
    TestCar car{t.car};
    car.m.cornering_front *= 0.8;
    car.v = 50;
    car.r = 50.0 / 300;
    stop.path(0, path);
    stop.estimate({0, 0, 0, 50, car.r, 0, 0});
    ASSERT_TRUE(stop.begin(0));
    for (int k = 1; k <= 4000; ++k) {
      const double now = k * 1e-3;
      if (gyro) stop.gyro(now, car.r);
      const StopCommand c = stop.step(now, car.v, car.delta, 6);
      car.step(1e-3, c.steer, 6);
    }
    const double reckoning_error = std::hypot(stop.pose().x - car.x, stop.pose().y - car.y);
    if (gyro) {
      EXPECT_LT(reckoning_error, 0.5) << reckoning_error;
      EXPECT_LT(off_path(path, car.x, car.y), 0.5);
    } else {
      EXPECT_GT(reckoning_error, 1.0) << reckoning_error;
    }
  }
}
