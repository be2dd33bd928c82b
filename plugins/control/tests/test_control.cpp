// Control algorithms on synthetic inputs: path tracker, wall follower, system manager.
#include "control/lateral_lqr.hpp"
#include "control/path_tracker.hpp"
#include "control/vehicle_tracking.hpp"
#include "control/common/mode_command.hpp"
#include "control/common/mode_stats.hpp"
#include "control/common/system_manager.hpp"
#include "control/common/wall_follower.hpp"

#include "av21.hpp"
#include "single_track.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::control;

namespace {

// The path tracker steering the AV-21.
TrackerParams av21_tracker() {
  TrackerParams tp;
  tp.wheelbase = av21_vehicle().wheelbase;
  return tp;
}

// A circle of radius r (counter-clockwise) at constant speed v, points every metre.
std::vector<PathPoint> circle(double r, double v) {
  std::vector<PathPoint> p;
  const int n = static_cast<int>(2 * M_PI * r);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    p.push_back({r * std::cos(a), r * std::sin(a), v});
  }
  return p;
}

}  // namespace

// On a circle, pure pursuit's steady steer is atan(wheelbase * curvature) (the look-ahead point
// on the circle subtends the arc the car drives); left turn: positive.
TEST(PathTracker, SteersTheCircleAndHoldsItsSpeed) {
  PathTracker t(av21_tracker());
  t.set_path(circle(100, 30));
  const Command c = t.control(100, 0, M_PI / 2, 30);  // on the circle, heading along it
  EXPECT_NEAR(c.steer, std::atan(t.params().wheelbase / 100), 1e-3);
  EXPECT_NEAR(t.cross_track(), 0, 1e-6);
  EXPECT_NEAR(c.target_speed, 30, 1e-9);
  EXPECT_DOUBLE_EQ(c.throttle, 0);
  EXPECT_DOUBLE_EQ(c.brake, 0);
  // 2 m outside the circle (to the right of the path): steer harder left.
  const Command out = t.control(102, 0, M_PI / 2, 30);
  EXPECT_GT(out.steer, c.steer);
  EXPECT_NEAR(t.cross_track(), -2, 1e-2);
  // Too slow: throttle.
  EXPECT_GT(t.control(100, 0, M_PI / 2, 20).throttle, 0.9);
}

// A straight at 60 m/s that drops to 20 m/s 100 m ahead: the tracker brakes before it, for the
// speed from which it can still brake at `decel` to 20 m/s in time.
TEST(PathTracker, BrakesAheadOfASlowerStretch) {
  std::vector<PathPoint> p;
  for (int i = 0; i <= 600; ++i) p.push_back({static_cast<double>(i), 0, i < 300 ? 60.0 : 20.0});
  TrackerParams tp = av21_tracker();
  tp.closed = false;
  PathTracker t(tp);
  t.set_path(p);
  // Beyond the preview (3 s x 60 m/s = 180 m): full speed.
  EXPECT_NEAR(t.control(0, 0, 0, 60).target_speed, 60, 1e-9);
  const Command c = t.control(200, 0, 0, 60);
  EXPECT_NEAR(c.target_speed, std::sqrt(20.0 * 20 + 2 * tp.decel * 100), 0.5);
  EXPECT_GT(c.brake, 0.9);
  EXPECT_NEAR(c.steer, 0, 1e-9);
  // No path: brake, wheel straight.
  PathTracker none(av21_tracker());
  const Command stop = none.control(0, 0, 0, 10);
  EXPECT_DOUBLE_EQ(stop.brake, 1);
  EXPECT_DOUBLE_EQ(stop.steer, 0);
}

using test_car::av21_model;
using test_car::Bicycle;

// The feedforward holds a steady turn: L kappa at low speed, plus the understeer gradient's term
// (the AV-21 is near neutral: a small negative K_v); the feedback steers toward the path.
TEST(LateralLqr, FeedforwardGainsAndSigns) {
  const LateralLqr l(av21_model(), LateralLqrParams{});
  const auto car = av21_model();
  const double wheelbase = car.lf + car.lr;
  EXPECT_NEAR(l.feedforward(0.01, 1.0), wheelbase * 0.01, 1e-5);
  const double kv = car.mass * (car.lr / car.cornering_front - car.lf / car.cornering_rear) / wheelbase;
  EXPECT_NEAR(l.feedforward(0.01, 40.0), wheelbase * 0.01 + kv * 1600 * 0.01, 1e-12);
  for (double v : {5.0, 20.0, 40.0, 80.0}) {
    const auto k = l.gains(v);  // the errors' four first
    for (double g : k) EXPECT_TRUE(std::isfinite(g));
    EXPECT_GT(k[0], 0);  // left of the path: steer right
    EXPECT_GT(k[2], 0);  // heading left of the path: steer right
  }
  PathErrors left;
  left.e_y = 1;
  EXPECT_LT(l.steer(left, 0, 20), 0);
  // The lateral error the feedback sees is bounded: 10 m off steers as 1.5 m off.
  PathErrors far = left;
  far.e_y = 10;
  PathErrors near = left;
  near.e_y = 1.5;
  EXPECT_DOUBLE_EQ(l.steer(far, 0, 20), l.steer(near, 0, 20));
  EXPECT_THROW(LateralLqr(LateralModel{}, LateralLqrParams{}), std::invalid_argument);
}

// Closed loop on the linear model it was designed for: from 1 m outside a 150 m circle at 20, 40
// and 60 m/s, the error is under 5 cm after 5 s and never overshoots past 0.5 m inside.
TEST(LateralLqr, ConvergesOnACircleAtEverySpeed) {
  const LateralLqr l(av21_model(), LateralLqrParams{});
  const double radius = 150, kappa = 1 / radius;
  for (double v : {20.0, 40.0, 60.0}) {
    Bicycle b{av21_model()};
    b.x = radius + 1, b.yaw = M_PI / 2;  // 1 m outside (right of the counter-clockwise path)
    double delta = 0, worst_inside = 0;
    for (int k = 0; k < 5000; ++k) {
      if (k % 10 == 0) {  // the controller at 100 Hz
        const double dist = std::hypot(b.x, b.y), path_yaw = std::atan2(b.y, b.x) + M_PI / 2;
        PathErrors e;
        e.e_y = radius - dist;  // left (inside) positive
        e.e_psi = std::remainder(b.yaw - path_yaw, 2 * M_PI);
        e.e_y_rate = v * std::sin(e.e_psi) + b.vy;
        e.e_psi_rate = b.r - v * kappa;
        delta = l.steer(e, kappa, v);
        worst_inside = std::max(worst_inside, e.e_y);
      }
      b.step(delta, v, 1e-3);
    }
    EXPECT_LT(std::abs(radius - std::hypot(b.x, b.y)), 0.05) << "at " << v << " m/s";
    EXPECT_LT(worst_inside, 0.5) << "at " << v << " m/s";
  }
}

// The tracker with the lqr law and feedforward pedals: on the circle it steers the feedforward
// (no error), and the pedals hold the speed against drag and rolling resistance.
TEST(PathTracker, LqrAndFeedforwardPedalsOnACircle) {
  TrackerParams tp;
  apply_vehicle(tp, av21_vehicle());
  tp.steer_law = SteerLaw::lqr;
  tp.pedal_law = PedalLaw::feedforward;
  tp.steer_delay = 0;
  PathTracker t(tp);
  t.set_path(circle(100, 30));
  // On the circle, heading along it, with the steady turn's yaw rate and sideslip-free.
  const auto car = av21_vehicle();
  const double ess = -car.lr / 100 + car.lf * car.mass * 900 / (100 * car.cornering_rear * car.wheelbase);
  const double yaw = M_PI / 2 + ess;
  const double bx = 100 - car.lr * std::cos(yaw), by = -car.lr * std::sin(yaw);
  const Command c = t.control(CarState{bx, by, yaw, 30, 30.0 / 100, 0});
  const LateralLqr l(av21_model(), LateralLqrParams{});
  EXPECT_NEAR(c.steer, l.feedforward(0.01, 30), 2e-3);
  EXPECT_NEAR(t.path_curvature(), 0.01, 2e-4);
  // Holding 30 m/s: the throttle that pays for drag and rolling resistance.
  const double need = 0.5 * car.air_density * car.drag_area * 900 + car.rolling_resistance * car.mass * 9.81;
  EXPECT_NEAR(c.throttle, need / std::min(car.max_drive_force, car.max_power / 30), 0.02);
  EXPECT_DOUBLE_EQ(c.brake, 0);
  // Slower than the path: more throttle; faster: brake.
  EXPECT_GT(t.control(CarState{bx, by, yaw, 25, 0.25, 0}).throttle, c.throttle);
  EXPECT_GT(t.control(CarState{bx, by, yaw, 35, 0.35, 0}).brake, 0);
}

// The AV-21 on an open path with the LQR and the feedforward pedals (the race's laws).
static TrackerParams race_laws() {
  TrackerParams tp;
  apply_vehicle(tp, av21_vehicle());
  tp.closed = false;
  tp.steer_law = SteerLaw::lqr;
  tp.pedal_law = PedalLaw::feedforward;
  return tp;
}

// A slow car (after a stop, or handed back by the wall follower) on a fast straight with a
// corner 60 m ahead: beyond what its speed previews, so the feedforward pedals drive it on.
// (They once previewed the slope at the target's speed, saw the corner, and braked it to a stop.)
TEST(PathTracker, FeedforwardPedalsDriveASlowCarOnTowardAFarCorner) {
  std::vector<PathPoint> p;
  for (int i = 0; i <= 800; ++i) p.push_back({static_cast<double>(i), 0, i < 60 ? 50.0 : 15.0});
  TrackerParams tp = race_laws();
  PathTracker t(tp);
  t.set_path(p);
  for (double v : {0.5, 2.0, 5.0, 10.0}) {
    const Command c = t.control(CarState{0, 0, 0, v, 0, 0});
    EXPECT_GT(c.throttle, 0.5) << "at " << v << " m/s";
    EXPECT_DOUBLE_EQ(c.brake, 0) << "at " << v << " m/s";
  }
  // Fast enough to see the corner: it brakes for it.
  const Command fast = t.control(CarState{0, 0, 0, 50, 0, 0});
  EXPECT_GT(fast.brake, 0);
}

// A car faster than its target where the path's speed rises ahead (a corner's exit): the error
// alone, so it brakes. It used to add the rise and throttle (Monza's first chicane on a mapped
// file: 0.48 of throttle 1.7 m/s over the target, the steering at its stop, into the wall).
TEST(PathTracker, FeedforwardPedalsNeverDriveACarThatIsFasterThanItsTarget) {
  std::vector<PathPoint> p;
  for (int i = 0; i <= 400; ++i) p.push_back({static_cast<double>(i), 0, 15.0 + 0.5 * i});  // rising fast
  TrackerParams tp = race_laws();
  PathTracker t(tp);
  t.set_path(p);
  const Command over = t.control(CarState{0, 0, 0, 17, 0, 0});  // 2 m/s over the 15 at the car
  EXPECT_DOUBLE_EQ(over.throttle, 0);
  EXPECT_GT(over.brake, 0);
  const Command under = t.control(CarState{0, 0, 0, 14, 0, 0});  // below it: the rise drives it on
  EXPECT_GT(under.throttle, 0);
}

// In a turn that takes all the grip at the car's speed but not at the target's, the car still
// brakes with the room the target's speed leaves (what the speed profile planned its braking
// with), not the fifth of the grip kept for a turn that takes everything.
TEST(PathTracker, ACarTooFastForATurnBrakesWithThePlannedRoom) {
  TrackerParams tp = race_laws();
  ASSERT_GT(tp.grip, 0);
  // A circle of radius R whose speed takes 70 % of the grip laterally.
  const double R = 100, v_plan = std::sqrt(0.7 * tp.grip * R);
  std::vector<PathPoint> p;
  for (int i = 0; i <= 600; ++i) {
    const double a = i / R;  // 1 m steps
    p.push_back({R * std::sin(a), R * (1 - std::cos(a)), v_plan});
  }
  PathTracker t(tp);
  t.set_path(p);
  // At 1.25 times the plan's speed the turn alone takes more than the grip (0.7 x 1.5625 > 1).
  const double v = 1.25 * v_plan;
  const Command c = t.control(CarState{0, 0, 0, v, v / R, 0});
  // The braking force asked for, back to an acceleration: more than the fifth of the grip.
  const Powertrain& pt = tp.powertrain;
  const double decel = (c.brake * pt.max_brake_force + pt.drag * v * v + pt.rolling) / pt.mass;
  EXPECT_EQ(c.throttle, 0);
  EXPECT_GT(decel, 0.3 * tp.grip) << "brake " << c.brake;
}

// u_w = w_θ y′(L) + w_d (d_w − side·gap), by hand.
TEST(WallFollower, ThePapersLawSignsAndSpeedPolicy) {
  WallFollowerParams p;  // right wall, gap 8, lookahead 10
  p.w_theta = 1;
  p.w_d = 0.05;
  p.fallback_speed = 30;
  p.decel = 5;
  WallFollower f(p);
  // Parallel wall 8 m to the right: nothing to do.
  EXPECT_NEAR(f.steering({{-8.0, 0.0}, true}), 0, 1e-12);
  // 10 m away: steer right (toward it), 0.05 * -2.
  EXPECT_NEAR(f.steering({{-10.0, 0.0}, true}), -0.1, 1e-12);
  // Wall curving left (y = -8 + 0.002 x^2): y'(10) = 0.04, steer left.
  EXPECT_NEAR(f.steering({{-8.0, 0.0, 0.002}, true}), 0.04, 1e-12);
  // Left wall 8 m away, parallel: nothing; 6 m away: steer right (away), 0.05 * -2.
  WallFollowerParams left = p;
  left.side = 1;
  EXPECT_NEAR(WallFollower(left).steering({{8.0}, true}), 0, 1e-12);
  EXPECT_NEAR(WallFollower(left).steering({{6.0}, true}), -0.1, 1e-12);
  // Speed: took over at 60 m/s; reduce at 5 m/s^2 toward 30: 50 after 2 s, 30 from 6 s on.
  f.engage(10.0, 60.0);
  EXPECT_NEAR(f.control(12.0, {{-8.0}, true}, 60).target_speed, 50, 1e-9);
  EXPECT_NEAR(f.control(20.0, {{-8.0}, true}, 40).target_speed, 30, 1e-9);
  EXPECT_GT(f.control(20.0, {{-8.0}, true}, 40).brake, 0.9);
  // Hold: the speed it took over at.
  WallFollowerParams hold = p;
  hold.reduce_speed = false;
  WallFollower h(hold);
  h.engage(0, 60);
  EXPECT_NEAR(h.control(20, {{-8.0}, true}, 60).target_speed, 60, 1e-9);
  // Taken over by a car that had stopped (the manager's resume_on_wall): it drives off to
  // restart_speed (8 m/s), with either policy; one slower than that but moving, too.
  f.engage(30.0, 0.0);
  const Command off = f.control(30.1, {{-8.0}, true}, 0);
  EXPECT_NEAR(off.target_speed, p.restart_speed, 1e-9);
  EXPECT_GT(off.throttle, 0.5);
  h.engage(30, 3);
  EXPECT_NEAR(h.control(40, {{-8.0}, true}, 3).target_speed, hold.restart_speed, 1e-9);
  // Steering clamps; an invalid wall brakes with a straight wheel.
  EXPECT_NEAR(f.control(12.0, {{-30.0}, true}, 50).steer, -p.max_steer, 1e-12);
  const Command lost = f.control(12.0, {{-8.0}, false}, 50);
  EXPECT_DOUBLE_EQ(lost.brake, 1);
  EXPECT_DOUBLE_EQ(lost.steer, 0);
}

TEST(SystemManager, EmergencyWallRecoveryAndSafeStop) {
  SystemManager m;  // recover 2 s, wall timeout 0.3 s, status timeout 0.5 s
  double t = 0;
  auto tick = [&](LocStatus s, bool wall) {
    t += 0.125;  // exact in binary: the 2 s of recovery is 16 ticks, not 20 ticks give or take one
    m.status(t, s);
    m.wall(t, wall);
    return m.update(t);
  };
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(tick(LocStatus::normal, true).happened);
  EXPECT_EQ(m.mode(), Mode::path);
  EXPECT_FALSE(tick(LocStatus::warning, true).happened);  // WARNING keeps the path
  Transition tr = tick(LocStatus::emergency, true);
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.to, Mode::wall);
  EXPECT_NE(tr.reason.find("EMERGENCY"), std::string::npos);
  // NORMAL again: not for 2 s (the first NORMAL tick starts the clock).
  for (int i = 0; i < 16; ++i) EXPECT_FALSE(tick(LocStatus::normal, true).happened) << i;
  tr = tick(LocStatus::normal, true);
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.to, Mode::path);
  // EMERGENCY with the wall lost too: straight to a safe stop.
  tr = tick(LocStatus::emergency, false);
  ASSERT_TRUE(tr.happened);  // the wall was seen 0.1 s ago: still valid
  EXPECT_EQ(tr.to, Mode::wall);
  const double lost_at = t - 0.125;  // the last valid wall
  do tr = tick(LocStatus::emergency, false);
  while (!tr.happened && t < lost_at + 1);
  EXPECT_EQ(tr.to, Mode::safe_stop);
  EXPECT_DOUBLE_EQ(t - lost_at, 0.375);  // the first tick past wall_timeout_s (0.3 s)
  // The safe stop holds while localization is bad, even if the wall comes back (no wall
  // follower has spoken here: SafeStopFollowsAWallThatHoldsASecond)...
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(tick(LocStatus::emergency, true).happened);
  // ...and ends once NORMAL has held.
  for (int i = 0; i < 16; ++i) EXPECT_FALSE(tick(LocStatus::normal, true).happened);
  EXPECT_EQ(tick(LocStatus::normal, true).to, Mode::path);
}

// resume_at WARNING: after an EMERGENCY, a WARNING held recover_after_s (the estimator corrected by
// the prior map again, GNSS still out) hands the path tracker the car back, from the wall follower
// and from a safe stop alike; with the paper's NORMAL it does not.
TEST(SystemManager, ResumeAtWarningHandsThePathBackOnTheMap) {
  for (const LocStatus resume : {LocStatus::normal, LocStatus::warning}) {
    for (const bool wall_seen : {true, false}) {
      ManagerParams p;
      p.resume_at = resume;
      SystemManager m(p);
      double t = 0;
      auto tick = [&](LocStatus s) {
        t += 0.125;
        m.status(t, s);
        m.wall(t, wall_seen);
        m.path_command(t);
        return m.update(t);
      };
      for (int i = 0; i < 4; ++i) tick(LocStatus::normal);
      tick(LocStatus::emergency);
      while (t < 3) tick(LocStatus::emergency);
      ASSERT_EQ(m.mode(), wall_seen ? Mode::wall : Mode::safe_stop);
      for (int i = 0; i < 16; ++i) EXPECT_FALSE(tick(LocStatus::warning).happened) << i;
      const Transition tr = tick(LocStatus::warning);
      if (resume == LocStatus::warning) {
        ASSERT_TRUE(tr.happened) << wall_seen;
        EXPECT_EQ(tr.to, Mode::path);
        EXPECT_NE(tr.reason.find("WARNING"), std::string::npos) << tr.reason;
        EXPECT_FALSE(tick(LocStatus::warning).happened) << "WARNING keeps the path";
        EXPECT_EQ(tick(LocStatus::emergency).to, wall_seen ? Mode::wall : Mode::safe_stop);
      } else {
        EXPECT_FALSE(tr.happened);
        for (int i = 0; i < 16; ++i) tick(LocStatus::normal);
        EXPECT_EQ(tick(LocStatus::normal).to, Mode::path) << "NORMAL held 2 s";
      }
    }
  }
}

// Stopped for want of a wall, with localization still in EMERGENCY: the car follows the wall
// again once it has been valid for wall_resume_s (1 s), report after report; an invalid report
// starts the second again; not with resume_on_wall off, nor with a wall follower gone silent.
TEST(SystemManager, SafeStopFollowsAWallThatHoldsASecond) {
  for (const int variant : {0, 1, 2}) {  // as is; resume_on_wall off; the wall follower silent
    ManagerParams p;
    p.resume_on_wall = variant != 1;
    SystemManager m(p);
    double t = 0;
    auto tick = [&](bool wall) {
      t += 0.125;
      m.status(t, LocStatus::emergency);
      m.wall(t, wall);
      if (variant != 2 || t < 1.0) m.wall_command(t);
      return m.update(t);
    };
    tick(false);
    while (m.mode() != Mode::safe_stop && t < 2) tick(false);
    ASSERT_EQ(m.mode(), Mode::safe_stop) << variant;
    const double stopped_at = t;
    while (t < 2.5) tick(false);
    // Valid for 0.875 s, then one invalid report: still stopped.
    for (int i = 0; i < 8; ++i) EXPECT_FALSE(tick(true).happened) << variant << " " << i;
    EXPECT_FALSE(tick(false).happened);
    const double from = t + 0.125;  // the run of valid walls that counts starts at the next tick
    Transition tr;
    do tr = tick(true);
    while (!tr.happened && t < from + 5);
    if (variant == 0) {
      ASSERT_TRUE(tr.happened);
      EXPECT_EQ(tr.to, Mode::wall);
      EXPECT_DOUBLE_EQ(t - from, 1.0);
      EXPECT_NE(tr.reason.find("valid wall again"), std::string::npos);
      EXPECT_GT(t, stopped_at + 1);
    } else {
      EXPECT_FALSE(tr.happened) << variant;
      EXPECT_EQ(m.mode(), Mode::safe_stop) << variant;
    }
  }
}

TEST(SystemManager, ASilentEstimatorIsAnEmergency) {
  SystemManager m;
  m.wall(0.0, true);
  EXPECT_FALSE(m.update(0.2).happened);  // nothing heard yet, within the timeout
  m.wall(0.5, true);
  const Transition tr = m.update(0.6);
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.to, Mode::wall);
  EXPECT_NE(tr.reason.find("no localization status"), std::string::npos);
  EXPECT_STREQ(mode_name(Mode::safe_stop), "SAFE_STOP");
}

// After a silence (which counts as EMERGENCY), NORMAL must hold its full time again.
TEST(SystemManager, NormalAfterASilenceHoldsItsTimeAgain) {
  SystemManager m;  // recover 2 s, status timeout 0.5 s
  m.status(10.0, LocStatus::normal);
  m.wall(10.0, true);
  EXPECT_FALSE(m.update(10.0).happened);
  m.wall(10.9, true);
  EXPECT_EQ(m.update(11.0).to, Mode::wall);  // silent since 10.0
  m.status(11.0, LocStatus::normal);
  m.wall(11.0, true);
  EXPECT_FALSE(m.update(11.0).happened);  // not back at once...
  for (double t = 11.25; t < 12.9; t += 0.25) {
    m.status(t, LocStatus::normal);
    m.wall(t, true);
    EXPECT_FALSE(m.update(t).happened) << t;
  }
  m.status(13.0, LocStatus::normal);
  EXPECT_EQ(m.update(13.0).to, Mode::path);  // ...but 2 s after the first NORMAL that followed it
}

// A stack started before its sensors: held for want of a status, then handed to the path
// tracker at the run's first NORMAL (nothing was lost), and WARNING before it does not count as
// that first; a later silence holds its full time again.
TEST(SystemManager, TheFirstNormalOfARunDrivesAtOnce) {
  SystemManager m;  // recover 2 s, status timeout 0.5 s
  const double t0 = 1.8e9;                            // the real clock: seconds since the epoch
  m.started(t0);
  EXPECT_FALSE(m.update(t0).happened);                // nothing heard yet, within the timeout
  EXPECT_EQ(m.update(t0 + 0.6).to, Mode::safe_stop);  // nothing heard: no localization status
  m.status(t0 + 1.5, LocStatus::warning);             // initialized, heading not known yet
  EXPECT_FALSE(m.update(t0 + 1.5).happened);
  m.status(t0 + 1.8, LocStatus::normal);
  EXPECT_EQ(m.update(t0 + 1.8).to, Mode::path);
  EXPECT_EQ(m.update(t0 + 3.0).to, Mode::safe_stop);  // silent since 1.8
  for (double t = 3.0; t < 4.9; t += 0.25) {
    m.status(t0 + t, LocStatus::normal);
    EXPECT_FALSE(m.update(t0 + t).happened) << t;
  }
  m.status(t0 + 5.0, LocStatus::normal);
  EXPECT_EQ(m.update(t0 + 5.0).to, Mode::path);
}

TEST(WallFollower, AMalformedWallBrakes) {
  WallFollower f;
  f.engage(0, 40);
  const Command c = f.control(1, {{NAN, 0.0}, true}, 40);
  EXPECT_DOUBLE_EQ(c.brake, 1);
  EXPECT_DOUBLE_EQ(c.steer, 0);
}

// wall_pedals cautious: the wall follower steers, the pedals that slow the car more win (not
// those of the lower target: each law's pedals are for its own line); a stale path command never.
// A controller whose commands stop (it died or hangs) is not forwarded: its last command would
// hold the car's last throttle. The path tracker silent for controller_timeout_s: the wall
// follower takes the car if a wall is seen, else SAFE_STOP; the wall follower silent while it
// drives: SAFE_STOP; no way back to a path tracker that is still silent. Controllers that have
// not yet sent a command are not silent (a run's start).
TEST(SystemManager, AControllerWhoseCommandsStopIsNotForwarded) {
  SystemManager m;  // controller timeout 0.25 s
  double t = 0;
  for (; t < 1.0; t += 0.01) {
    m.status(t, LocStatus::normal);
    m.wall(t, true);
    m.wall_command(t);
    EXPECT_FALSE(m.update(t).happened) << "t " << t << ": no path command yet is not a silent tracker";
    m.path_command(t);
  }
  // The path tracker stops at t = 1.
  Transition tr;
  for (; t < 1.4 && !tr.happened; t += 0.01) {
    m.status(t, LocStatus::normal);
    m.wall(t, true);
    m.wall_command(t);
    tr = m.update(t);
  }
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.to, Mode::wall);
  EXPECT_NEAR(t, 1.26, 0.02);
  EXPECT_NE(tr.reason.find("the path tracker's commands stopped"), std::string::npos) << tr.reason;
  // Localization NORMAL all along, but the tracker still silent: the car stays with the wall.
  for (; t < 4.0; t += 0.01) {
    m.status(t, LocStatus::normal);
    m.wall(t, true);
    m.wall_command(t);
    EXPECT_FALSE(m.update(t).happened) << "t " << t;
  }
  // Then the wall follower stops too: SAFE_STOP.
  for (tr = {}; t < 4.5 && !tr.happened; t += 0.01) {
    m.status(t, LocStatus::normal);
    m.wall(t, true);
    tr = m.update(t);
  }
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.to, Mode::safe_stop);
  EXPECT_NE(tr.reason.find("the wall follower's commands stopped"), std::string::npos) << tr.reason;
  // Without a wall, a silent path tracker is SAFE_STOP straight away.
  SystemManager n;
  n.status(0, LocStatus::normal);
  n.path_command(0);
  tr = n.update(0.3);
  EXPECT_EQ(tr.to, Mode::safe_stop);
  EXPECT_NE(tr.reason.find("no wall to follow"), std::string::npos) << tr.reason;
}

TEST(SystemManager, CautiousPedalsSlowTheCarMore) {
  const Pedals wall{0.4, 0.0, 25.0}, path_slow{0.0, 0.8, 12.0}, path_fast{1.0, 0.0, 60.0};
  EXPECT_EQ(cautious(wall, path_slow, true).brake, 0.8);
  EXPECT_EQ(cautious(wall, path_slow, true).target_speed, 12.0);
  EXPECT_EQ(cautious(wall, path_fast, true).throttle, 0.4);
  EXPECT_EQ(cautious(wall, path_slow, false).throttle, 0.4);  // stale: the wall follower's
  // The path aims lower but brakes less than the wall follower: the wall follower's pedals, the lower target.
  const Pedals wall_braking{0.0, 0.5, 27.0}, path_lower{0.0, 0.1, 26.0};
  EXPECT_EQ(cautious(wall_braking, path_lower, true).brake, 0.5);
  EXPECT_EQ(cautious(wall_braking, path_lower, true).target_speed, 26.0);
}

// What the system manager's node sends in each mode (mode_command.hpp).
TEST(ModeCommand, ThePathTrackersOrTheWallFollowersOrAFullBrake) {
  ManagerParams p;
  const ControllerCommand path{1.0, {0.1, 0.6, 0.0, 30.0}}, wall{1.0, {-0.05, 0.4, 0.0, 25.0}};
  ModeCommand c = command_for(Mode::path, 1.05, path, wall, p);
  EXPECT_EQ(c.forward, Forwarded::path);
  EXPECT_EQ(c.command.steer, 0.1);
  EXPECT_EQ(c.command.throttle, 0.6);
  EXPECT_EQ(c.command.target_speed, 30.0);
  c = command_for(Mode::path, 1.05, std::nullopt, wall, p);
  EXPECT_EQ(c.forward, Forwarded::none) << "nothing to forward yet";
  EXPECT_EQ(c.command.brake, 1.0);
  EXPECT_EQ(c.command.throttle, 0.0);
  c = command_for(Mode::wall, 1.05, path, wall, p);
  EXPECT_EQ(c.forward, Forwarded::wall);
  EXPECT_EQ(c.command.steer, -0.05);
  EXPECT_EQ(c.command.throttle, 0.4) << "the wall follower's pedals (the paper)";
  c = command_for(Mode::wall, 1.05, path, std::nullopt, p);
  EXPECT_EQ(c.forward, Forwarded::none);
  EXPECT_EQ(c.command.brake, 1.0);
}

TEST(ModeCommand, CautiousPedalsTakeAFreshPathCommandsWhenTheySlowTheCarMore) {
  ManagerParams p;
  p.cautious_pedals = true;
  const ControllerCommand path{1.0, {0.1, 0.0, 0.8, 12.0}}, wall{1.0, {-0.05, 0.4, 0.0, 25.0}};
  ModeCommand c = command_for(Mode::wall, 1.05, path, wall, p);  // the path command fresh: 0.05 s old
  EXPECT_EQ(c.forward, Forwarded::wall);
  EXPECT_EQ(c.command.steer, -0.05) << "the wall follower steers";
  EXPECT_EQ(c.command.throttle, 0.0);
  EXPECT_EQ(c.command.brake, 0.8);
  EXPECT_EQ(c.command.target_speed, 12.0);
  c = command_for(Mode::wall, 1.2, path, wall, p);  // the path command stale
  EXPECT_EQ(c.command.throttle, 0.4);
  EXPECT_EQ(c.command.brake, 0.0);
  EXPECT_EQ(c.command.target_speed, 25.0);
}

TEST(ModeCommand, ASafeStopBrakesAndSteersAlongAWallStillSeen) {
  ManagerParams p;
  const ControllerCommand path{1.0, {0.1, 0.6, 0.0, 30.0}}, wall{1.0, {-0.05, 0.4, 0.0, 25.0}};
  ModeCommand c = command_for(Mode::safe_stop, 1.25, path, wall, p);  // the wall follower's command 0.25 s old
  EXPECT_EQ(c.forward, Forwarded::none);
  EXPECT_EQ(c.command.steer, -0.05);
  EXPECT_EQ(c.command.throttle, 0.0);
  EXPECT_EQ(c.command.brake, 1.0);
  EXPECT_EQ(c.command.target_speed, 0.0);
  EXPECT_EQ(command_for(Mode::safe_stop, 1.4, path, wall, p).command.steer, 0.0) << "the wall follower's command too old";
  EXPECT_EQ(command_for(Mode::safe_stop, 1.0, path, std::nullopt, p).command.steer, 0.0);
}

// stop_on_path: with no wall seen, the safe stop steers the path tracker's wheel (on dead
// reckoning) while its command is fresh; a wall still seen comes first.
TEST(ModeCommand, ASafeStopOnThePathSteersThePathTrackersWheelWhenNoWallIsSeen) {
  ManagerParams p;
  p.stop_on_path = true;
  const ControllerCommand path{1.0, {0.1, 0.6, 0.0, 30.0}}, wall{1.0, {-0.05, 0.4, 0.0, 25.0}};
  EXPECT_EQ(command_for(Mode::safe_stop, 1.25, path, wall, p).command.steer, -0.05) << "the wall first";
  const ModeCommand c = command_for(Mode::safe_stop, 1.05, path, std::nullopt, p);
  EXPECT_EQ(c.command.steer, 0.1);
  EXPECT_EQ(c.command.throttle, 0.0);
  EXPECT_EQ(c.command.brake, 1.0);
  EXPECT_EQ(command_for(Mode::safe_stop, 1.4, path, wall, p).command.steer, 0.0) << "both too old (command_timeout_s 0.1 s)";
  p.stop_on_path = false;
  EXPECT_EQ(command_for(Mode::safe_stop, 1.05, path, std::nullopt, p).command.steer, 0.0) << "the paper's: straight";
}

TEST(ModeCommand, ModeNamesAndNumbers) {
  EXPECT_STREQ(controller_name(Mode::path), "path_tracker");
  EXPECT_STREQ(controller_name(Mode::wall), "wall_follower");
  EXPECT_STREQ(controller_name(Mode::safe_stop), "safe_stop");
  EXPECT_EQ(mode_number(Mode::path), 0);
  EXPECT_EQ(mode_number(Mode::wall), 2);
  EXPECT_EQ(mode_number(Mode::safe_stop), 3);
}

// The record for the summary (mode_stats.hpp): transitions, entries, and the time from one step
// to the next counted for the mode of the later step.
TEST(ModeStats, TransitionsEntriesAndTimeInEachMode) {
  ModeStats s;
  EXPECT_TRUE(s.step(0.0, Transition{}, Mode::path)) << "the first step tells the mode";
  EXPECT_FALSE(s.step(0.01, Transition{}, Mode::path));
  const Transition to_wall{true, Mode::path, Mode::wall, "localization EMERGENCY"};
  EXPECT_TRUE(s.step(0.02, to_wall, Mode::wall));
  EXPECT_FALSE(s.step(0.05, Transition{}, Mode::wall));
  EXPECT_TRUE(s.step(0.06, Transition{true, Mode::wall, Mode::safe_stop, "no wall"}, Mode::safe_stop));
  EXPECT_EQ(s.transitions(), 2u);
  EXPECT_EQ(s.entered(Mode::path), 0u);
  EXPECT_EQ(s.entered(Mode::wall), 1u);
  EXPECT_EQ(s.entered(Mode::safe_stop), 1u);
  EXPECT_EQ(s.reason(), "no wall");
  EXPECT_DOUBLE_EQ(s.time_in(Mode::path), 0.01);
  EXPECT_NEAR(s.time_in(Mode::wall), 0.04, 1e-12);
  EXPECT_NEAR(s.time_in(Mode::safe_stop), 0.01, 1e-12);
  std::vector<std::string> names;
  for (const auto& [name, value] : s.metrics()) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"transitions", "entered_PATH", "time_s_PATH", "entered_WALL_FOLLOW", "time_s_WALL_FOLLOW",
                                             "entered_SAFE_STOP", "time_s_SAFE_STOP"}));
  EXPECT_EQ(transition_line(to_wall, 1.5), "PATH -> WALL_FOLLOW at t = 1.500000 s: localization EMERGENCY");
}

// The car's side watched (the vehicle interface's status wired): its watchdog stopping the car,
// a silent steering or brake report, or its status silent stop the car, from PATH or from the
// wall; the car drives again once the car's side has been well for recover_after_s; a handover
// to the drive-by-wire never ends. Unwatched, none of it counts.
TEST(SystemManager, TheCarsSideStopsTheCarWhenItIsNotWell) {
  auto healthy = [](SystemManager& m, double t) {
    m.status(t, LocStatus::normal);
    m.path_command(t);
  };
  SystemManager m;  // recover 2 s, vehicle timeout 0.5 s
  m.watch_vehicle();
  double t = 0;
  for (; t < 3.0; t += 0.02) {  // well for 2 s and more: started
    healthy(m, t), m.vehicle(t, {});
    EXPECT_FALSE(m.update(t).happened) << t;
  }
  m.vehicle(t, {.stopping = true});
  healthy(m, t);
  Transition tr = m.update(t);
  EXPECT_EQ(tr.to, Mode::safe_stop);
  EXPECT_EQ(tr.reason, "the vehicle interface is stopping the car: the commands do not reach it");
  t += 0.02;
  double back = -1;
  std::string why;
  for (; t < 7.0; t += 0.02) {
    healthy(m, t), m.vehicle(t, {});  // well again from 3.02 s
    if (const Transition b = m.update(t); b.happened) back = t, why = b.reason;
  }
  EXPECT_NEAR(back, 5.02, 0.021);  // 2 s after
  EXPECT_EQ(why, "the car's side well again: back to the path");
  EXPECT_EQ(m.mode(), Mode::path);
  m.vehicle(t, {.steering_silent = true});
  healthy(m, t);
  EXPECT_NE(m.update(t).reason.find("steering report silent"), std::string::npos);
  for (t += 0.02; t < 10.0; t += 0.02) healthy(m, t), m.vehicle(t, {}), m.update(t);
  EXPECT_EQ(m.mode(), Mode::path);
  m.vehicle(t, {.brake_silent = true});
  healthy(m, t);
  EXPECT_NE(m.update(t).reason.find("brake report silent"), std::string::npos);
  for (t += 0.02; t < 13.0; t += 0.02) healthy(m, t), m.vehicle(t, {}), m.update(t);
  EXPECT_EQ(m.mode(), Mode::path);
  const double last = t - 0.02;  // its last status: the interface falls silent
  for (; t < last + 0.49; t += 0.02) {
    healthy(m, t);
    EXPECT_FALSE(m.update(t).happened) << t;
  }
  t = last + 0.52;
  healthy(m, t);
  tr = m.update(t);
  EXPECT_EQ(tr.to, Mode::safe_stop);
  EXPECT_EQ(tr.reason, "the vehicle interface silent: no status for 0.52 s");
  t += 0.02;
  m.vehicle(t, {.handed_over = true});
  for (; t < 22.0; t += 0.02) {
    healthy(m, t), m.vehicle(t, {});
    EXPECT_FALSE(m.update(t).happened) << t;
  }
  EXPECT_EQ(m.mode(), Mode::safe_stop);  // handed over: for good

  SystemManager unwatched;
  for (t = 0; t < 2.0; t += 0.02) {
    healthy(unwatched, t), unwatched.vehicle(t, {.stopping = true});
    EXPECT_FALSE(unwatched.update(t).happened);
  }
}

// A car side not well at the start (the drive-by-wire's reports not heard yet: it starts after the
// stack; the interface says so once their first timeout has passed) holds the car, and its first
// good status hands it over at once, as the first NORMAL does.
TEST(SystemManager, TheCarsSideFirstWellAtTheStartDrivesAtOnce) {
  SystemManager m;
  m.watch_vehicle();
  double t = 0;
  m.status(t, LocStatus::normal), m.path_command(t), m.vehicle(t, {});  // (before the reports' timeout)
  EXPECT_FALSE(m.update(t).happened);
  t = 0.12;
  m.status(t, LocStatus::normal), m.path_command(t), m.vehicle(t, {.steering_silent = true});
  EXPECT_EQ(m.update(t).to, Mode::safe_stop);
  for (t = 0.14; t < 3.0; t += 0.02) {
    m.status(t, LocStatus::normal), m.path_command(t), m.vehicle(t, {.steering_silent = true, .brake_silent = true});
    EXPECT_FALSE(m.update(t).happened) << t;
  }
  m.status(t, LocStatus::normal), m.path_command(t), m.vehicle(t, {});
  EXPECT_EQ(m.update(t).to, Mode::path);
}

// From the wall follower too, and not back to the wall while the car's side is not well.
TEST(SystemManager, TheCarsSideStopsTheWallFollowerToo) {
  SystemManager m;
  m.watch_vehicle();
  double t = 0;
  m.status(t, LocStatus::emergency), m.wall(t, true), m.wall_command(t), m.vehicle(t, {});
  EXPECT_EQ(m.update(t).to, Mode::wall);
  for (t = 0.02; t < 5.0; t += 0.02) {  // well until 3 s: started
    m.status(t, LocStatus::emergency), m.wall(t, true), m.wall_command(t);
    m.vehicle(t, {.stopping = t >= 3.0 && t < 3.5});
    const Transition tr = m.update(t);
    if (t < 3.0 || t >= 3.52) continue;
    if (t < 3.01) EXPECT_EQ(tr.to, Mode::safe_stop);
    else EXPECT_FALSE(tr.happened) << t;  // held while stopping
  }
  EXPECT_EQ(m.mode(), Mode::safe_stop);  // well since 3.5 s: 2 s to go
  for (; t < 6.0; t += 0.02) m.status(t, LocStatus::emergency), m.wall(t, true), m.wall_command(t), m.vehicle(t, {}), m.update(t);
  EXPECT_EQ(m.mode(), Mode::wall);
}
