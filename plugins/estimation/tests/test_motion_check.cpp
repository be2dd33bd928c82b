// The motion check (motion_check.hpp): what it learns of the wheels, what it catches, and the
// localizer that races on through receivers drifting together where the map cannot tell.
#include "estimation/common/localizer.hpp"
#include "estimation/common/motion_check.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

using namespace brickyard::estimation;

namespace {

// A straight drive at `v` along x, a fix at 20 Hz of one receiver (its error `fix_error(t)` plus
// noise `fix_noise`), dead reckoning on wheels `wheel_scale(t)` times the truth. Feeds `check` from
// t0 to t1 and returns the first time a fix was judged off (-1: none).
struct StraightFeed {
  double v = 40, fix_noise = 0.02;
  std::function<double(double)> wheel_scale = [](double) { return 1.01; };
  std::function<Eigen::Vector2d(double)> fix_error = [](double) { return Eigen::Vector2d::Zero(); };
  std::mt19937 rng{7};
  double reckoned = 0, last_t = 0;
  int judged = 0;

  double feed(MotionCheck& check, double t0, double t1) {
    std::normal_distribution<double> n(0, fix_noise);
    double first_off = -1;
    for (double t = t0; t < t1 - 1e-9; t += 0.05) {
      reckoned += v * wheel_scale(t) * (t - last_t);
      last_t = t;
      const Eigen::Vector2d fix = Eigen::Vector2d(v * t, 0) + fix_error(t) + Eigen::Vector2d(n(rng), n(rng));
      const MotionVerdict verdict = check.observe(0, {t, fix, fix_noise * fix_noise, {reckoned, 0}, 0.0, {v * t, 0}});
      judged += verdict.judged;
      if (verdict.off && first_off < 0) first_off = t;
      if (!verdict.off) check.learn(t, verdict);
    }
    return first_off;
  }
};

}  // namespace

// Wheels 1 % high: the scale learnt to 1/1.01, nothing judged before learn_s of healthy windows,
// no clean fix judged off; then a receiver drifting 0.3 m/s along the road (what a map of a
// straight between parallel walls cannot see) is off within 2 s, and one frozen at once.
TEST(MotionCheck, LearnsTheWheelsScaleThenCatchesAFixMovingUnlikeTheCar) {
  MotionCheck check(MotionParams{});
  StraightFeed drive;
  EXPECT_LT(drive.feed(check, 0, 20), 0) << "nothing judged while learning";
  EXPECT_EQ(drive.judged, 0);
  EXPECT_LT(drive.feed(check, 20, 60), 0) << "no clean fix off";
  EXPECT_GT(drive.judged, 0);
  EXPECT_NEAR(check.scale(), 1 / 1.01, 2e-4);
  EXPECT_EQ(check.wheel_scale(), check.scale()) << "1 % off: dead reckoning takes it";
  EXPECT_LT(check.spread_along(), 1e-3) << "what is left is the fixes' noise";
  MotionCheck drifted = check;
  StraightFeed drifting = drive;
  drifting.fix_error = [](double t) { return t >= 60 ? Eigen::Vector2d(0.3 * (t - 60), 0) : Eigen::Vector2d::Zero(); };
  const double caught = drifting.feed(drifted, 60, 70);
  EXPECT_GT(caught, 60.0);
  EXPECT_LT(caught, 62.0);
  StraightFeed frozen = drive;
  frozen.fix_error = [v = drive.v](double t) { return t >= 60 ? Eigen::Vector2d(-v * (t - 60), 0) : Eigen::Vector2d::Zero(); };
  EXPECT_NEAR(frozen.feed(check, 60, 70), 60.05, 0.03) << "a fix standing still while the car moves";
}

// Wheels as good as GNSS can tell (the simulator's): the scale learnt within its own spread of 1,
// and dead reckoning keeps 1 (a learnt 1.00003 taken on IMS cost the map's outage 0.05 m).
TEST(MotionCheck, WheelsAsGoodAsGnssCanTellAreTakenAsTheyAre) {
  MotionCheck check(MotionParams{});
  StraightFeed drive;
  drive.wheel_scale = [](double) { return 1.0; };
  drive.feed(check, 0, 120);
  EXPECT_NE(check.scale(), 1.0);
  EXPECT_LT(std::abs(check.scale() - 1), 3 * check.scale_sigma());
  EXPECT_EQ(check.wheel_scale(), 1.0);
}

// Wheels whose scale wanders by 2 % (slip, a tyre's growth): the spreads learnt wide, no clean fix
// judged off, and the same drift not caught: a poor odometry makes the check catch less, never
// more.
TEST(MotionCheck, APoorOdometryIsJudgedLoosely) {
  MotionCheck check(MotionParams{});
  StraightFeed drive;
  drive.wheel_scale = [](double t) { return 1.0 + 0.02 * std::sin(t); };
  EXPECT_LT(drive.feed(check, 0, 60), 0);
  EXPECT_GT(check.spread_along(), 5e-3);
  drive.fix_error = [](double t) { return t >= 60 ? Eigen::Vector2d(0.3 * (t - 60), 0) : Eigen::Vector2d::Zero(); };
  EXPECT_LT(drive.feed(check, 60, 70), 0);
}

// A window is as long as window_s, never across an outage: a receiver back after 10 s starts
// a new one (its old fixes are not compared with its new ones).
TEST(MotionCheck, AReceiverBackFromAnOutageStartsANewWindow) {
  MotionCheck check(MotionParams{});
  StraightFeed drive;
  drive.feed(check, 0, 40);
  MotionCheck gap = check;
  StraightFeed after = drive;
  after.judged = 0;
  after.reckoned += drive.v * 1.01 * 10;  // the car drove on for 10 s unheard
  after.last_t = 50;
  after.fix_error = [](double) { return Eigen::Vector2d(5, 0); };  // and its receiver came back 5 m off
  after.feed(gap, 50, 52.9);
  EXPECT_EQ(after.judged, 0) << "no window yet";
  EXPECT_LT(after.feed(gap, 52.9, 60), 0) << "5 m off throughout: moving as the car does";
  EXPECT_GT(after.judged, 0);
}

namespace {

// Laps of a stadium: 400 m straights and half circles of 100 m radius at 40 m/s, wheels 0.5 %
// high, both receivers at 20 Hz (noise 2 cm, each off by `fix_error(t)`, claiming 2 cm), and a map
// that says where the car is across the road (10 cm) but nothing of how far along (30 m): the
// worst error of the filter after 5 s, and the localizer.
struct StadiumDrive {
  std::function<Eigen::Vector2d(double)> fix_error = [](double) { return Eigen::Vector2d::Zero(); };
  double seconds = 120, worst = 0, worst_after_catch = 0;  // the latter from 0.5 s after the first catch

  Localizer run(double window_s) {
    LocalizerParams p;
    p.manager.receivers = 2;
    p.manager.witness_timeout_s = 0.3;
    p.roll_filter_s = 0;
    p.witness.enabled = true;
    p.motion.window_s = window_s;
    Localizer loc(p);
    std::mt19937 rng(11);
    std::normal_distribution<double> noise(0, 0.02);
    const double v = 40, r = 100, straight = 400, lap_s = (2 * straight + 2 * M_PI * r) / v;
    double x = 0, y = 0, yaw = 0;
    std::vector<std::pair<double, Eigen::Vector3d>> past;  // the truth, for the map's late poses
    worst = worst_after_catch = 0;
    for (int k = 0; k * 0.01 < seconds; ++k) {
      const double t = 0.01 * k, along = std::fmod(t, lap_s) * v;
      const bool turning = std::fmod(along, straight + M_PI * r) >= straight;
      const double w = turning ? v / r : 0.0;
      loc.speed(v * 1.005);
      loc.imu(t, w, v * w);
      if (k % 5 == 0) {
        const Eigen::Vector2d truth(x, y), e = fix_error(t);
        loc.fixes(t, {Fix{0, truth + e + Eigen::Vector2d(noise(rng), noise(rng)), p.lever[0], 0.02},
                      Fix{1, truth + e + Eigen::Vector2d(noise(rng), noise(rng)), p.lever[1], 0.02}});
      }
      past.push_back({t, {x, y, yaw}});
      if (k % 10 == 5 && t > 1) {
        const auto& [stamp, pose] = past[past.size() - 11];
        const Eigen::Rotation2Dd turn(pose.z());
        const Eigen::Matrix2d cov = turn.toRotationMatrix() * Eigen::Vector2d(900, 0.01).asDiagonal() * turn.toRotationMatrix().transpose();
        loc.scan_pose(stamp, pose.head<2>(), cov);
      }
      const double error = (loc.filter().position() - Eigen::Vector2d(x, y)).norm();
      if (t > 5 && loc.filter().initialized()) worst = std::max(worst, error);
      if (loc.first_motion_catch_s() >= 0 && t > loc.first_motion_catch_s() + 0.5) worst_after_catch = std::max(worst_after_catch, error);
      const double mid = yaw + 0.5 * w * 0.01;
      x += v * std::cos(mid) * 0.01;
      y += v * std::sin(mid) * 0.01;
      yaw += w * 0.01;
    }
    return loc;
  }
};

}  // namespace

// Both receivers drifting together at (0.2, -0.2) m/s from 60 s on, claiming RTK-fixed (the
// simulator's drift_both): the map, which cannot tell how far along the car is, never disagrees
// enough, and without the motion check the filter follows them metres off. With it both are
// caught within 2 s, the filter put back on the car's own travel, and the map and dead reckoning
// carry it; a clean drive is never judged off.
TEST(Localizer, ReceiversDriftingTogetherAreCaughtByTheCarsOwnMotion) {
  StadiumDrive clean;
  const Localizer quiet = clean.run(3.0);
  EXPECT_EQ(quiet.witness().refusals(), 0u) << "no false alarm through straights and turns";
  EXPECT_EQ(quiet.motion_catches(), 0u);
  EXPECT_LT(clean.worst, 0.2);
  StadiumDrive d;
  d.fix_error = [](double t) { return Eigen::Vector2d(Eigen::Vector2d(0.2, -0.2) * std::max(0.0, t - 60)); };
  d.run(0);
  EXPECT_GT(d.worst, 3.0) << "without the check the filter follows the receivers";
  const Localizer loc = d.run(3.0);
  EXPECT_GT(loc.first_motion_catch_s(), 60.0);
  EXPECT_LT(loc.first_motion_catch_s(), 62.0);
  EXPECT_TRUE(loc.witness().caught(0));
  EXPECT_TRUE(loc.witness().caught(1));
  EXPECT_LT(d.worst, 0.6) << "the drift the filter took before the catch";
  EXPECT_LT(d.worst_after_catch, 0.1) << "undone at the catch: where the car's own travel puts it";
}
