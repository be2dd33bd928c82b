// Resilient localization: every branch of the paper's update selection with numbers worked out
// by hand, the metre-valued distance, the filter, the baselines' behaviour and the manager.
#include "estimation/common/epoch_gather.hpp"
#include "estimation/common/estimator_report.hpp"
#include "estimation/common/localization_manager.hpp"
#include "estimation/common/localizer.hpp"
#include "estimation/common/sample_feed.hpp"
#include "estimation/common/update_selection.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include <cmath>

using namespace brickyard::estimation;

TEST(UpdateSelection, AllWithinEpsilonUsesTheClosestOrAllByLikelihood) {
  Selection s = select_updates({0.10, 0.05}, 0.2, 5.0);  // the paper's weighting
  EXPECT_EQ(s.which, UpdateCase::single);
  EXPECT_EQ(s.weight, (std::vector<double>{0, 1}));
  // Both consistent (within 3 sigma): equal weights.
  s = select_updates({0.10, 0.05}, 0.2, 5.0, Weighting::likelihood, {2.0, 1.0});
  EXPECT_EQ(s.which, UpdateCase::single);
  EXPECT_EQ(s.weight, (std::vector<double>{0.5, 0.5}));
  // 4 and 1 sigma: excess 16 - 9 = 7 and 0 -> e^-3.5 / (1 + e^-3.5) and 1 / (1 + e^-3.5).
  s = select_updates({0.15, 0.05}, 0.2, 5.0, Weighting::likelihood, {4.0, 1.0});
  EXPECT_NEAR(s.weight[0], std::exp(-3.5) / (1 + std::exp(-3.5)), 1e-12);
  EXPECT_NEAR(s.weight[1], 1 / (1 + std::exp(-3.5)), 1e-12);
}

TEST(UpdateSelection, AllWithinDeltaIsTheWeightedSum) {
  // ΣΔ = 4: λ = 1 - 1/4 = 0.75 and 1 - 3/4 = 0.25 (they already sum to 1 for two fixes).
  Selection s = select_updates({1.0, 3.0}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::weighted);
  EXPECT_DOUBLE_EQ(s.weight[0], 0.75);
  EXPECT_DOUBLE_EQ(s.weight[1], 0.25);
  // One within ε and one not is still "not all within ε": weighted. ΣΔ = 0.5: 0.8 / 0.2.
  s = select_updates({0.1, 0.4}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::weighted);
  EXPECT_DOUBLE_EQ(s.weight[0], 0.8);
  EXPECT_DOUBLE_EQ(s.weight[1], 0.2);
}

TEST(UpdateSelection, LikelihoodWeightingPrefersTheConsistentFix) {
  // d = 1 and 5 sigma: excess 0 and 25 - 9 = 16 -> 1 / (1 + e^-8) and e^-8 / (1 + e^-8).
  Selection s = select_updates({0.3, 0.4}, 0.2, 5.0, Weighting::likelihood, {1.0, 5.0});
  EXPECT_EQ(s.which, UpdateCase::weighted);
  EXPECT_NEAR(s.weight[0], 1 / (1 + std::exp(-8.0)), 1e-12);
  EXPECT_NEAR(s.weight[1], std::exp(-8.0) / (1 + std::exp(-8.0)), 1e-12);
  // Far apart in sigma, no underflow: 30 and 40 sigma -> all on the first.
  s = select_updates({1.0, 2.0}, 0.2, 5.0, Weighting::likelihood, {30.0, 40.0});
  EXPECT_NEAR(s.weight[0], 1.0, 1e-12);
}

TEST(UpdateSelection, ThreeFixesNormaliseTheWeights) {
  // ΣΔ = 6: λ = 5/6, 4/6, 3/6, sum 2 -> 5/12, 4/12, 3/12.
  Selection s = select_updates({1, 2, 3}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::weighted);
  EXPECT_NEAR(s.weight[0], 5.0 / 12, 1e-12);
  EXPECT_NEAR(s.weight[1], 4.0 / 12, 1e-12);
  EXPECT_NEAR(s.weight[2], 3.0 / 12, 1e-12);
}

TEST(UpdateSelection, SomeWithinDeltaUsesOnlyThose) {
  Selection s = select_updates({2.0, 7.0}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::partial);
  EXPECT_EQ(s.weight, (std::vector<double>{1, 0}));
  // Two of three feasible: weighted among them, ΣΔ = 4 -> 0.75 / 0.25.
  s = select_updates({1, 3, 8}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::partial);
  EXPECT_DOUBLE_EQ(s.weight[0], 0.75);
  EXPECT_DOUBLE_EQ(s.weight[1], 0.25);
  EXPECT_DOUBLE_EQ(s.weight[2], 0);
}

TEST(UpdateSelection, NoneWithinDeltaRejectsAll) {
  Selection s = select_updates({6, 9}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::rejected);
  EXPECT_EQ(s.weight, (std::vector<double>{0, 0}));
  EXPECT_EQ(select_updates({}, 0.2, 5.0).which, UpdateCase::predict_only);
  // A lone fix within δ is used as it is.
  s = select_updates({3}, 0.2, 5.0);
  EXPECT_EQ(s.which, UpdateCase::single);
  EXPECT_EQ(s.weight, (std::vector<double>{1}));
}

TEST(UpdateSelection, DeltaIsInMetres) {
  // Isotropic S: Δ is the Euclidean distance, whatever S's size.
  EXPECT_NEAR(metric_delta({0.3, 0.4}, Eigen::Matrix2d::Identity() * 0.01), 0.5, 1e-12);
  EXPECT_NEAR(metric_delta({0.3, 0.4}, Eigen::Matrix2d::Identity() * 100), 0.5, 1e-12);
  // S = diag(0.04, 0.01), e = (0.2, 0) along the unsure axis: Mahalanobis 1, times the largest
  // sigma 0.2 -> 0.2 m, the Euclidean distance.
  EXPECT_NEAR(metric_delta({0.2, 0}, Eigen::Vector2d(0.04, 0.01).asDiagonal().toDenseMatrix()), 0.2, 1e-12);
  // Across the sure axis it counts double: e = (0, 0.2) -> Mahalanobis 2 -> 0.4 m.
  EXPECT_NEAR(metric_delta({0, 0.2}, Eigen::Vector2d(0.04, 0.01).asDiagonal().toDenseMatrix()), 0.4, 1e-12);
}

TEST(PoseFilter, DeadReckonsStraightAndRound) {
  PoseFilter f;
  f.init(0, 0, 0, 0.1, 0.01);
  for (int i = 0; i < 125; ++i) f.predict(0.008, 20.0, 0.0);
  EXPECT_NEAR(f.state()(PoseFilter::X), 20.0, 1e-9);
  EXPECT_NEAR(f.state()(PoseFilter::Y), 0.0, 1e-9);
  // A quarter circle of radius 100 m at 20 m/s (no sideslip learnt yet: K = 0).
  PoseFilter g;
  g.init(0, 0, 0, 0.1, 0.01);
  const double w = 0.2, T = M_PI / 2 / w;
  const int n = static_cast<int>(std::round(T / 0.001));
  for (int i = 0; i < n; ++i) g.predict(T / n, 20.0, w);
  EXPECT_NEAR(g.state()(PoseFilter::X), 100.0, 1e-3);
  EXPECT_NEAR(g.state()(PoseFilter::Y), 100.0, 1e-3);
  EXPECT_GT(g.cov()(0, 0), f.cov()(0, 0) * 0.5);  // uncertainty grows with travel
}

TEST(PoseFilter, LeverArmIsTakenOut) {
  PoseFilter f;
  f.init(10, 20, M_PI / 2, 0.1, 0.01);  // facing north: the antenna 1.606 m ahead is north
  Eigen::Vector2d base = f.base_from_antenna({10.05, 21.606}, {1.606, -0.05, 1.0});
  EXPECT_NEAR(base.x(), 10.0, 1e-12);
  EXPECT_NEAR(base.y(), 20.0, 1e-12);
}

namespace {
PoseFilter after_outage(double seconds) {
  PoseFilter f;
  f.init(0, 0, 0, 0.02, 0.002);
  const int n = static_cast<int>(seconds / 0.008);
  for (int i = 0; i < n; ++i) f.predict(0.008, 70.0, 0.0);
  return f;
}
}  // namespace

TEST(Policies, ResilientWeighsTheCloseFixAndGatedLetsBadFixesInAfterALongRejection) {
  PolicyParams p;
  // Fresh filter, one receiver 0.4 m off: the weighted sum leans on the good one.
  PoseFilter r;
  r.init(0, 0, 0, 0.02, 0.002);
  std::vector<Fix> fixes = {{0, {1.606 + 0.4, 0.05}, {1.606, 0.05, 1.0}, 0.015}, {1, {1.606 + 0.01, -0.05}, {1.606, -0.05, 1.0}, 0.015}};
  EpochResult e = apply_fixes(r, fixes, Policy::resilient, p);
  EXPECT_EQ(e.which, UpdateCase::weighted);
  EXPECT_LT(std::abs(r.position().x()), 0.05);
  // After a 10 s outage at 70 m/s the covariance has grown: 8 m off passes the chi-square gate,
  // while Δ, in metres, still rejects it.
  PoseFilter g = after_outage(10), rs = g;
  const double x = g.position().x();
  std::vector<Fix> bad = {{0, {x + 1.606, 8.05}, {1.606, 0.05, 1.0}, 0.015}, {1, {x + 1.606, 7.95}, {1.606, -0.05, 1.0}, 0.015}};
  EpochResult eg = apply_fixes(g, bad, Policy::gated, p);
  EXPECT_EQ(eg.which, UpdateCase::weighted) << "gated should accept both after the outage";
  EpochResult er = apply_fixes(rs, bad, Policy::resilient, p);
  EXPECT_EQ(er.which, UpdateCase::rejected);
  EXPECT_GT(er.delta[0], 5.0);
  EXPECT_NEAR(rs.position().y(), 0.0, 1e-9);
  // The same bad fixes on a fresh filter: the gate holds.
  PoseFilter fresh = after_outage(0.1);
  bad[0].antenna.x() = bad[1].antenna.x() = fresh.position().x() + 1.606;
  EXPECT_EQ(apply_fixes(fresh, bad, Policy::gated, p).which, UpdateCase::rejected);
  // Naive takes everything.
  PoseFilter nv = after_outage(0.1);
  EXPECT_EQ(apply_fixes(nv, bad, Policy::naive, p).which, UpdateCase::weighted);
  EXPECT_GT(nv.position().y(), 3.0);
}

// Every receiver lost while an independent witness (the map localizer's poses) is taken: WARNING,
// the car keeps its path; the witness silent for witness_timeout_s: EMERGENCY; the receivers
// back: down a level at a time, as ever. Without witness_timeout_s the witness counts for nothing.
TEST(LocalizationManager, AWitnessKeepsEmergencyAwayWhileItIsTaken) {
  for (const double timeout : {0.0, 0.3}) {
    ManagerParams mp;  // 2 receivers, EMERGENCY after 0.3 s, recover after 1 s, timeout 0.25 s
    mp.witness_timeout_s = timeout;
    LocalizationManager m(mp);
    double t = 0;
    for (; t < 1; t += 0.05) m.on_fix(0, t, true), m.on_fix(1, t, true), m.update(t);
    const double lost = t;
    for (; t < lost + 5; t += 0.05) {  // both silent, a witness every 0.05 s
      m.on_witness(t);
      const Status s = m.update(t);
      if (t < lost + 0.6) continue;  // silent past fix_timeout_s, then emergency_after_s
      ASSERT_EQ(s, timeout > 0 ? Status::warning : Status::emergency) << t - lost;
      if (timeout > 0) {
        EXPECT_NE(m.reason().find("located on the map"), std::string::npos) << m.reason();
      }
    }
    const double witness_gone = t - 0.05;
    for (; t < witness_gone + 0.3 - 1e-9; t += 0.05) EXPECT_EQ(m.update(t), timeout > 0 ? Status::warning : Status::emergency);
    EXPECT_EQ(m.update(witness_gone + 0.31), Status::emergency) << "the witness silent too";
  }
}

TEST(LocalizationManager, WarningEmergencyAndHysteresis) {
  ManagerParams mp;  // 2 receivers, EMERGENCY after 0.3 s, recover after 1 s, timeout 0.25 s
  LocalizationManager m(mp);
  int k = 0;  // epochs of 0.05 s
  auto epoch = [&](bool ok0, bool ok1) {
    const double t = 0.05 * k++;
    m.on_fix(0, t, ok0);
    m.on_fix(1, t, ok1);
    return m.update(t);
  };
  for (int i = 0; i < 20; ++i) EXPECT_EQ(epoch(true, true), Status::normal);
  EXPECT_EQ(epoch(false, true), Status::warning);  // one rejected
  EXPECT_EQ(epoch(true, true), Status::warning);   // hysteresis: not back yet
  for (int i = 0; i < 6; ++i) EXPECT_EQ(epoch(false, false), Status::warning) << i;  // 0 .. 0.25 s
  EXPECT_EQ(epoch(false, false), Status::emergency);                                 // 0.30 s
  for (int i = 0; i < 20; ++i) EXPECT_EQ(epoch(true, true), Status::emergency) << i;  // 0 .. 0.95 s
  for (int i = 0; i < 20; ++i) EXPECT_EQ(epoch(true, true), Status::warning) << i;    // 1.0 .. 1.95 s
  EXPECT_EQ(epoch(true, true), Status::normal);                                       // 2.0 s
  // Silence counts as rejection once it lasts fix_timeout_s: both silent from t0.
  const double t0 = 0.05 * (k - 1);
  EXPECT_EQ(m.update(t0 + 0.2), Status::normal);
  EXPECT_EQ(m.update(t0 + 0.3), Status::warning);    // both silent since t0 + 0.25 (seen at 0.3)
  EXPECT_EQ(m.update(t0 + 0.55), Status::warning);
  EXPECT_EQ(m.update(t0 + 0.61), Status::emergency);  // 0.31 s after it was first seen
}

TEST(Localizer, HeadingFromTravelThenRollFromTheImu) {
  LocalizerParams p;
  p.manager.receivers = 1;
  p.lever[0] = {1.606, 0.05, 1.0};
  Localizer loc(p);
  loc.speed(20);
  // Driving north-east at 20 m/s, a fix every 0.05 s: the heading is taken after 5 m.
  const double yaw = M_PI / 4;
  int k = 0;
  for (; k < 20 && !loc.filter().initialized(); ++k) {
    const double t = 0.05 * k, s = 20 * t;
    EXPECT_EQ(loc.status(t), Status::warning);  // not localized yet
    loc.imu(t, 0.0, 0.0);
    Fix f{0, {s * std::cos(yaw) + 1.606 * std::cos(yaw), s * std::sin(yaw) + 1.606 * std::sin(yaw)}, p.lever[0], 0.015};
    loc.fixes(t, {f});
  }
  ASSERT_TRUE(loc.filter().initialized());
  EXPECT_NEAR(loc.filter().state()(PoseFilter::YAW), yaw, 1e-9);
  EXPECT_EQ(k, 6);  // 5 m at 20 m/s: the fix at 0.25 s
  // Steady turn on a banked road: f_y = v w + g sin(roll). After a few time constants the
  // roll estimate is the banking's.
  const double roll = -0.16, w = 0.2;
  for (int i = 0; i < 2000; ++i) loc.imu(0.3 + 0.008 * i, w, 20 * w + 9.81 * std::sin(roll));  // 16 time constants
  EXPECT_NEAR(loc.filter().roll(), roll, 1e-6);
}

// A receiver that sends NaN (broken, or forged) costs nothing but its own fixes (NaN
// fixes made the fusion reject the healthy receiver too, EMERGENCY for 15 of 16 s).
TEST(Localizer, AMalformedFixCostsOnlyItself) {
  LocalizerParams p;
  p.manager.receivers = 2;
  Localizer loc(p);
  loc.speed(20);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 200; ++k) {
    const double t = 0.05 * k, s = 20 * t;
    loc.imu(t, 0.0, 0.0);
    loc.imu(t + 0.01, nan, 0.0);  // dropped, not a step to NaN
    Fix good{0, {s, 0.0}, p.lever[0], 0.02}, bad{1, {nan, 0.0}, p.lever[1], 0.02};
    loc.fixes(t, {good, bad});
    loc.speed(nan);  // kept at 20
  }
  ASSERT_TRUE(loc.filter().initialized());
  EXPECT_TRUE(loc.filter().state().allFinite());
  EXPECT_NEAR(loc.filter().state()(PoseFilter::X), 20 * 0.05 * 199, 0.5);
  EXPECT_EQ(loc.malformed(), 3u * 200u);
  EXPECT_EQ(loc.rejected(), 0u) << "the good receiver is never rejected for the other's NaN";
  EXPECT_NE(loc.status(0.05 * 199), Status::emergency);
}

// Fixes delivered after IMU samples stamped later (a sample DDS resent, a loaded host: the split
// main job's stack restarted on a busy machine took its fixes up to 0.2 s late at 35 m/s and
// rejected them all for 48 s): each is carried to now by the filter's motion since its stamp,
// not taken as now (7 m behind the car, past delta). One older than the history is dropped.
TEST(Localizer, ALateFixIsCarriedToNowByTheMotionSinceItsStamp) {
  LocalizerParams p;
  p.manager.receivers = 2;
  p.lever[0] = {1.606, 0.05, 0.9};
  p.lever[1] = {1.606, -0.05, 0.9};
  p.roll_filter_s = 0;
  Localizer loc(p);
  const double v = 35, w = 0.1, radius = v / w;  // a steady turn
  auto antenna = [&](double t, int r) {
    const double yaw = w * t;
    const Eigen::Vector2d base(radius * std::sin(yaw), radius * (1 - std::cos(yaw)));
    return Eigen::Vector2d(base + Eigen::Rotation2Dd(yaw) * p.lever[r].head<2>());
  };
  const double late = 0.2;
  std::vector<std::pair<double, Fix>> queue;  // fixes waiting for delivery
  Status status = Status::warning;
  double t = 0;
  for (int i = 0; i < 1000; ++i) {
    t = 0.01 * i;
    loc.speed(v);
    loc.imu(t, w, 0.0);
    // The receivers apart: one at whole epochs, the other 23 ms after (unsynchronised clocks).
    if (i % 5 == 0) queue.push_back({t, Fix{0, antenna(t, 0), p.lever[0], 0.02}});
    if (i % 5 == 2) queue.push_back({t + 0.003, Fix{1, antenna(t + 0.003, 1), p.lever[1], 0.02}});
    while (!queue.empty() && queue.front().first <= t - late) {
      loc.fixes(queue.front().first, {queue.front().second});
      queue.erase(queue.begin());
    }
    status = loc.status(t);
  }
  ASSERT_TRUE(loc.filter().initialized());
  EXPECT_EQ(loc.rejected(), 0u);
  EXPECT_EQ(status, Status::normal);
  EXPECT_GT(loc.late(), 300u);
  EXPECT_NEAR(loc.late_max_s(), late, 0.011);
  const Eigen::Vector2d truth = antenna(t, 0) - Eigen::Rotation2Dd(w * t) * p.lever[0].head<2>();
  EXPECT_LT((loc.filter().position() - truth).norm(), 0.05);
  EXPECT_NEAR(std::remainder(loc.filter().state()(PoseFilter::YAW) - w * t, 2 * M_PI), 0.0, 2e-3);
  // Older than the history (about 1.5 s of predictions): dropped, not taken.
  const auto rejected = loc.rejected();
  loc.fixes(t - 3.0, {Fix{0, antenna(t - 3.0, 0), p.lever[0], 0.02}});
  EXPECT_EQ(loc.too_late(), 1u);  // the history is kept from the first IMU sample on
  EXPECT_EQ(loc.rejected(), rejected);
}

// On the real clock the estimator steps when an IMU sample arrives; one that arrived 18 ms late
// (its sender stalled) left the filter at its stamp while the estimate went out as now: 1.4 m
// behind the car at 77 m/s (evidence.car_on_wires_race). The pose at a later time is the
// filter's carried by its speed and yaw rate, at most max_s, and says how far short it is.
TEST(Localizer, ThePoseAtALaterTimeIsCarriedByTheFiltersMotion) {
  LocalizerParams p;
  p.manager.receivers = 1;
  p.roll_filter_s = 0;
  Localizer loc(p);
  const double v = 77, w = 0.05;
  double t = 0;
  for (int i = 0; i < 400 && (i < 200 || !loc.filter().initialized()); ++i) {
    t = 0.008 * i;
    loc.speed(v);
    loc.imu(t, w, 0.0);
    const double yaw = w * t, r = v / w;
    if (i % 6 == 0) loc.fixes(t, {Fix{0, {r * std::sin(yaw), r * (1 - std::cos(yaw))}, p.lever[0], 0.02}});
  }
  ASSERT_TRUE(loc.filter().initialized());
  ASSERT_DOUBLE_EQ(loc.time(), t);
  const auto& x = loc.filter().state();
  const Localizer::Pose same = loc.pose_at(t, 0.1);  // the filter's own time: its pose
  EXPECT_EQ(same.x, x(PoseFilter::X));
  EXPECT_EQ(same.y, x(PoseFilter::Y));
  EXPECT_EQ(same.carried_s, 0.0);
  EXPECT_EQ(loc.pose_at(t - 0.05, 0.1).x, x(PoseFilter::X)) << "never carried back";
  const Localizer::Pose later = loc.pose_at(t + 0.018, 0.1);
  const double travelled = std::hypot(later.x - same.x, later.y - same.y);
  EXPECT_NEAR(travelled, x(PoseFilter::SPEED) * 0.018, 1e-9);
  EXPECT_NEAR(later.yaw - same.yaw, x(PoseFilter::YAW_RATE) * 0.018, 1e-12);
  EXPECT_NEAR(later.carried_s, 0.018, 1e-12);
  EXPECT_EQ(later.short_s, 0.0);
  // The chord of a constant turn: heading at the middle of the step.
  EXPECT_NEAR(std::atan2(later.y - same.y, later.x - same.x), same.yaw + 0.5 * x(PoseFilter::YAW_RATE) * 0.018, 1e-9);
  const Localizer::Pose far = loc.pose_at(t + 0.5, 0.1);  // at most max_s
  EXPECT_NEAR(far.carried_s, 0.1, 1e-12);
  EXPECT_NEAR(far.short_s, 0.4, 1e-12);
  EXPECT_NEAR(std::hypot(far.x - same.x, far.y - same.y), x(PoseFilter::SPEED) * 0.1, 1e-3);
}

// The real clock's receivers stamp their fixes a few milliseconds apart and the estimator may
// take one before the other: the gather makes them one epoch again (each fix keeping its stamp),
// lets a lone fix go once it has waited wait_s, and keeps one receiver's two fixes apart.
TEST(EpochGather, PairsTheReceiversFixesOfAnEpochAndLetsALoneOneGo) {
  EpochGather g(2, 0.01, 0.05);
  auto fix = [](int r) { return Fix{r, {0.0, 0.0}, Eigen::Vector3d::Zero(), 0.02}; };
  g.add(1.000, fix(0));
  EXPECT_TRUE(g.release(1.001).empty());
  g.add(1.003, fix(1));
  auto out = g.release(1.004);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].fixes.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].t, 1.003);
  EXPECT_DOUBLE_EQ(out[0].fixes[0].stamp, 1.000);
  EXPECT_DOUBLE_EQ(out[0].fixes[1].stamp, 1.003);
  // A receiver alone (the other silent): handed on once it has waited 0.05 s.
  g.add(2.000, fix(1));
  EXPECT_TRUE(g.release(2.049).empty());
  out = g.release(2.051);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].fixes.size(), 1u);
  // One receiver's two fixes are two epochs, the other's fix joins the nearer of them, and a fix
  // from before the held ones goes first.
  g.add(3.000, fix(0));
  g.add(3.005, fix(0));
  g.add(3.006, fix(1));
  g.add(2.980, fix(1));
  out = g.release(3.1);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_DOUBLE_EQ(out[0].fixes[0].stamp, 2.980);
  EXPECT_EQ(out[1].fixes.size(), 1u);  // 3.000 (0)
  EXPECT_EQ(out[2].fixes.size(), 2u);  // 3.005 (0) with 3.006 (1)
  EXPECT_EQ(g.held(), 0u);
  // A stamp that is not finite is refused; fixes stamped far ahead of the clock (forged, or a
  // wrong clock) are not held past kMaxHeld epochs.
  EXPECT_FALSE(g.add(std::numeric_limits<double>::quiet_NaN(), fix(0)));
  EXPECT_FALSE(g.add(std::numeric_limits<double>::infinity(), fix(0)));
  EXPECT_EQ(g.held(), 0u);
  for (int k = 0; k < 100; ++k) g.add(1e6 + k, fix(0));
  EXPECT_EQ(g.release(4.0).size(), 100u - EpochGather::kMaxHeld);
  EXPECT_EQ(g.held(), EpochGather::kMaxHeld);
}

// Issue 16's outage on the real clock: the receivers' fixes 3 ms apart and taken by the estimator
// as they come. Epoch by epoch of one fix each, the receivers never agree with each other in one
// epoch and the filter never comes back; gathered, it does (as on the sim clock).
TEST(Localizer, ComesBackOnTheRealClockWithItsReceiversFixesGathered) {
  for (bool gathered : {false, true}) {
    LocalizerParams p;
    p.manager.receivers = 2;
    p.lever[0] = p.lever[1] = Eigen::Vector3d::Zero();
    p.roll_filter_s = 0;
    Localizer loc(p);
    EpochGather gather(2, 0.01, 0.05);
    double t = 0, last = 0;
    Status status = Status::warning;
    auto drive = [&](double until, bool fixes, double speed_factor) {
      for (; t < until - 1e-9; t += 0.001) {
        const int ms = static_cast<int>(std::lround(t * 1000));
        if (ms % 10 == 0) {
          loc.speed(20 * speed_factor);
          loc.imu(t, 0.0, 0.0);
          last = t;
        }
        const bool r0 = ms % 50 == 0, r1 = ms % 50 == 3;
        if (fixes && (r0 || r1)) {
          const Fix f{r0 ? 0 : 1, Eigen::Vector2d(20 * t, r0 ? 0.0 : 0.02), Eigen::Vector3d::Zero(), 0.015};
          if (gathered) gather.add(t, f);
          else loc.fixes(t, {f});
        }
        if (gathered)
          for (auto& e : gather.release(last)) loc.fixes(e.t, e.fixes);
        status = loc.status(t);
      }
    };
    drive(10, true, 1.0);
    ASSERT_TRUE(loc.filter().initialized());
    EXPECT_EQ(status, Status::normal);
    drive(20, false, 1.1);  // the outage: no fixes, the wheels read 10 % high
    EXPECT_EQ(status, Status::emergency);
    drive(30, true, 1.0);
    const double error = (loc.filter().position() - Eigen::Vector2d(20 * last, 0)).norm();
    if (gathered) {
      EXPECT_EQ(loc.reacquisitions(), 1u);
      EXPECT_LT(error, 0.1);
      EXPECT_EQ(status, Status::normal);
      EXPECT_GT(loc.epochs_of(UpdateCase::single), 0u);
    } else {
      EXPECT_EQ(loc.reacquisitions(), 0u);
      EXPECT_GT(error, 15.0);
      EXPECT_EQ(status, Status::emergency);
    }
  }
}

// The rule of coming back: receivers that agree with each other and move as the prediction does
// for the window; not one receiver alone, not receivers apart, not fixes that jump about.
TEST(Reacquisition, AgreeingReceiversThatMoveWithThePrediction) {
  ReacquireParams p;  // agree 0.3 m, motion 0.3 m, window 1 s, two receivers
  const Eigen::Vector2d drift(12, -3);  // the prediction is this far from the truth
  auto epoch = [&](double t, double apart, double jitter) {
    const Eigen::Vector2d truth(20 * t, 0), filter = truth - drift;
    return std::make_pair(std::vector<Eigen::Vector2d>{truth + Eigen::Vector2d(jitter, apart / 2), truth - Eigen::Vector2d(0, apart / 2)}, filter);
  };
  Reacquisition r(p);
  std::optional<Reacquired> at;
  double when = -1;
  for (int k = 0; k <= 40 && !at; ++k) {
    const auto [z, x] = epoch(0.05 * k, 0.1, 0.0);
    at = r.observe(0.05 * k, z, x);
    if (at) when = 0.05 * k;
  }
  ASSERT_TRUE(at);
  EXPECT_NEAR(when, 1.0, 1e-9);                               // after the window, not before
  EXPECT_NEAR((at->position - Eigen::Vector2d(20 * when, 0)).norm(), 0, 1e-9);  // the receivers' mean
  EXPECT_NEAR(at->turn, 0, 1e-9);
  // Receivers 0.5 m apart never agree.
  Reacquisition apart(p);
  for (int k = 0; k <= 100; ++k) {
    const auto [z, x] = epoch(0.05 * k, 0.5, 0.0);
    EXPECT_FALSE(apart.observe(0.05 * k, z, x));
  }
  // Fixes jumping by a metre every other epoch (a receiver's noise x30) never move as predicted.
  Reacquisition jumpy(p);
  for (int k = 0; k <= 100; ++k) {
    const auto [z, x] = epoch(0.05 * k, 0.0, k % 2 ? 1.0 : 0.0);
    EXPECT_FALSE(jumpy.observe(0.05 * k, {z[0], z[0]}, x));
  }
  // One receiver has nothing to agree with.
  Reacquisition one(p);
  for (int k = 0; k <= 100; ++k) {
    const auto [z, x] = epoch(0.05 * k, 0.0, 0.0);
    EXPECT_FALSE(one.observe(0.05 * k, {z[0]}, x));
  }
}

// Dead reckoning that drifted in heading too (a yaw-rate bias during the outage): the fixes trace
// the predicted path turned by 0.05 rad and moved. The offset between them changes as the car
// drives, so only a fit that turns the path finds them in agreement; it returns the turn.
TEST(Reacquisition, FindsTheHeadingErrorOfDeadReckoning) {
  ReacquireParams p;
  for (double err : {0.05, -0.2, 0.5}) {
    Reacquisition r(p);
    const double c = std::cos(err), sn = std::sin(err);
    std::optional<Reacquired> at;
    for (int k = 0; k <= 40 && !at; ++k) {
      const double t = 0.1 * k;
      const Eigen::Vector2d truth(60 * t, 0.5 * t * t);  // 60 m/s, bending gently
      // The filter's path: the truth turned by -err about (30, -40) and shifted by (8, 5).
      const Eigen::Vector2d q = truth - Eigen::Vector2d(30, -40);
      const Eigen::Vector2d filter = Eigen::Vector2d(30, -40) + Eigen::Vector2d(c * q.x() + sn * q.y(), -sn * q.x() + c * q.y()) + Eigen::Vector2d(8, 5);
      at = r.observe(t, {truth + Eigen::Vector2d(0, 0.05), truth - Eigen::Vector2d(0, 0.05)}, filter);
    }
    if (std::abs(err) > p.max_turn) {
      EXPECT_FALSE(at) << err;  // past the largest turn the fit may make
      continue;
    }
    ASSERT_TRUE(at) << err;
    EXPECT_NEAR(at->turn, err, 1e-6);
  }
  // The same drift with the turn taken as zero (the old rule): never.
  ReacquireParams still = p;
  still.min_span_m = 1e6;
  Reacquisition r(still);
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.1 * k;
    const Eigen::Vector2d truth(60 * t, 0), filter(60 * t * std::cos(0.05) + 8, -60 * t * std::sin(0.05) + 5);
    EXPECT_FALSE(r.observe(t, {truth, truth}, filter));
  }
}

// A 10 s outage with a wheel speed 10 % high: dead reckoning ends 20 m out, every healthy fix is
// rejected and the localization stays in EMERGENCY for good — unless the rule brings it back.
TEST(Localizer, ComesBackAfterAnOutageThatDriftedPastDelta) {
  for (bool enabled : {false, true}) {
    LocalizerParams p;
    p.manager.receivers = 2;
    p.lever[0] = p.lever[1] = Eigen::Vector3d::Zero();
    p.reacquire.enabled = enabled;
    p.roll_filter_s = 0;
    Localizer loc(p);
    double t = 0, last = 0;  // the time of the last IMU sample: where the filter is
    Status status = Status::warning;
    auto drive = [&](double until, bool fixes, double speed_factor) {
      for (; t < until - 1e-9; t += 0.01) {
        loc.speed(20 * speed_factor);
        loc.imu(t, 0.0, 0.0);
        if (fixes && std::fmod(t + 1e-9, 0.05) < 0.01) {
          const Eigen::Vector2d at(20 * t, 0);
          loc.fixes(t, {Fix{0, at, p.lever[0], 0.015}, Fix{1, at + Eigen::Vector2d(0, 0.02), p.lever[1], 0.015}});
        }
        status = loc.status(t);  // the manager is stepped as the plugin steps it
        last = t;
      }
    };
    drive(10, true, 1.0);
    ASSERT_TRUE(loc.filter().initialized());
    EXPECT_EQ(status, Status::normal);
    drive(20, false, 1.1);  // the outage: no fixes, the wheels read 10 % high
    EXPECT_EQ(status, Status::emergency);
    EXPECT_GT(std::abs(loc.filter().position().x() - 20 * last), 15.0);
    drive(30, true, 1.0);   // healthy fixes again
    const double error = (loc.filter().position() - Eigen::Vector2d(20 * last, 0)).norm();
    if (enabled) {
      EXPECT_EQ(loc.reacquisitions(), 1u);
      EXPECT_LT(error, 0.1);
      EXPECT_EQ(status, Status::normal);
    } else {
      EXPECT_EQ(loc.reacquisitions(), 0u);
      EXPECT_GT(error, 15.0);
      EXPECT_EQ(status, Status::emergency);
    }
  }
}

// The scan mapper's pose as a second estimate (docs/mapping.md): not taken while fixes are
// accepted (the mapper's prior is this filter's estimate: the same information twice), taken in an
// outage — each one stamped a LiDAR sweep ago and moved to now by the filter's motion since — and
// a pose far off refused by the gate.
TEST(Localizer, TakesTheScanPoseOnlyWhileGnssIsDegraded) {
  auto run = [](bool scan, Eigen::Vector2d scan_offset, std::uint64_t* updates, std::uint64_t* refused, std::uint64_t* before) {
    LocalizerParams p;
    p.manager.receivers = 1;
    p.lever[0] = Eigen::Vector3d::Zero();
    p.roll_filter_s = 0;
    Localizer loc(p);
    const double v = 20;
    for (double t = 0; t < 15.0 - 1e-9; t += 0.01) {
      loc.speed(v * 1.03);  // the wheels read 3 % high: dead reckoning drifts 0.6 m a second
      loc.imu(t, 0.0, 0.0);
      const bool gnss = t < 5.0;
      if (gnss && std::fmod(t + 1e-9, 0.05) < 0.01) loc.fixes(t, {Fix{0, {v * t, 0}, p.lever[0], 0.015}});
      if (scan && t > 0.5 && std::fmod(t + 1e-9, 0.05) < 0.01) {
        const double stamp = t - 0.05;  // the frame's time: a sweep ago
        loc.scan_pose(stamp, Eigen::Vector2d(v * stamp, 0) + scan_offset, Eigen::Matrix2d::Identity() * 0.01);
      }
      if (std::abs(t - 4.99) < 1e-6) *before = loc.scan_updates();
    }
    *updates = loc.scan_updates();
    *refused = loc.scan_refused();
    return (loc.filter().position() - Eigen::Vector2d(v * 14.99, 0)).norm();
  };
  std::uint64_t updates = 0, refused = 0, before = 0;
  const double without = run(false, {0, 0}, &updates, &refused, &before);
  const double with = run(true, {0, 0}, &updates, &refused, &before);
  EXPECT_GT(without, 4.0) << "10 s of dead reckoning on wheels 3 % high";
  EXPECT_LT(with, 0.5) << "the scan poses, moved to now, hold it (a lag remains: the filter has no state for a wheel-speed scale error)";
  EXPECT_EQ(before, 0u) << "none taken while the fixes were accepted";
  EXPECT_GT(updates, 150u);
  const double far = run(true, {0, 8.0}, &updates, &refused, &before);
  EXPECT_GT(refused, 0u);
  EXPECT_GT(far, 4.0) << "poses 8 m off are refused, not followed";
}

// The estimator's step (sample_feed.hpp): a step's samples, read input by input (the IMU's out of
// order here), reach the localizer as hand-made calls in time order would: an IMU sample before a
// fix of its stamp, both receivers' fixes of one stamp as one epoch, a "no fix" nowhere.
TEST(SampleFeed, AStepsSamplesReachTheLocalizerInTimeOrder) {
  Receivers rx;
  rx.lever[0] = {1.6, 0.5, 1.0};
  rx.lever[1] = {1.6, -0.5, 1.0};
  LocalizerParams p;
  p.manager.receivers = 2;
  p.lever[0] = rx.lever[0];
  p.lever[1] = rx.lever[1];
  Localizer fed(p), by_hand(p);
  fed.speed(20);
  by_hand.speed(20);
  auto fix = [&](int r, double t) { return rx.fix(r, {20 * t + 1.6, rx.lever[r].y()}, 0.02, 0.01); };
  for (int step = 0; step < 100; ++step) {
    const double t0 = 0.05 * step, tf = t0 + 0.02;  // the fixes stamped as the third IMU sample
    std::vector<ImuSample> imu;
    for (int i = 4; i >= 0; --i) imu.push_back({t0 + 0.01 * i, 0.0, 0.0});
    const std::vector<GnssSample> gnss = {{tf, true, fix(0, tf)}, {t0 + 0.03, false, fix(0, t0 + 0.03)}, {tf, true, fix(1, tf)}};
    feed_in_time_order(fed, nullptr, imu, gnss);
    for (int i = 0; i < 3; ++i) by_hand.imu(t0 + 0.01 * i, 0.0, 0.0);
    by_hand.fixes(tf, {fix(0, tf), fix(1, tf)});
    for (int i = 3; i < 5; ++i) by_hand.imu(t0 + 0.01 * i, 0.0, 0.0);
  }
  ASSERT_TRUE(fed.filter().initialized());
  EXPECT_GT(fed.epochs(), 50u);
  EXPECT_EQ(fed.epochs(), by_hand.epochs());
  EXPECT_TRUE(fed.filter().state() == by_hand.filter().state());
  EXPECT_TRUE(fed.filter().cov() == by_hand.filter().cov());
}

// On the real clock the receivers' fixes come a few milliseconds apart: through the gather they are
// one epoch, without it two.
TEST(SampleFeed, OnTheRealClockTheGatherMakesOneEpochOfTheReceiversFixes) {
  Receivers rx;
  LocalizerParams p;
  p.manager.receivers = 2;
  Localizer gathered(p), apart(p);
  EpochGather gather(2, 0.01, 0.05);
  for (Localizer* loc : {&gathered, &apart}) loc->speed(20);
  for (int step = 0; step < 100; ++step) {
    const double t0 = 0.05 * step;
    const std::vector<ImuSample> imu = {{t0, 0.0, 0.0}, {t0 + 0.025, 0.0, 0.0}};
    const std::vector<GnssSample> gnss = {{t0 + 0.010, true, rx.fix(0, {20 * (t0 + 0.010), 0.0}, 0.02, 0.02)},
                                          {t0 + 0.013, true, rx.fix(1, {20 * (t0 + 0.013), 0.0}, 0.02, 0.02)}};
    feed_in_time_order(gathered, &gather, imu, gnss);
    feed_in_time_order(apart, nullptr, imu, gnss);
  }
  EXPECT_EQ(gather.held(), 0u) << "each epoch let go once whole";
  EXPECT_GT(gathered.epochs(), 80u);
  EXPECT_NEAR(static_cast<double>(apart.epochs()), 2.0 * static_cast<double>(gathered.epochs()), 2.0);
}

TEST(SampleFeed, AFixIsItsReceiversOrTheFirstOnes) {
  Receivers rx;
  rx.lever[0] = {1, 2, 3};
  rx.lever[1] = {4, 5, 6};
  const Fix second = rx.fix(1, {10, 20}, 0.03, 0.02);
  EXPECT_EQ(second.receiver, 1);
  EXPECT_EQ(second.lever, rx.lever[1]);
  EXPECT_EQ(second.antenna, Eigen::Vector2d(10, 20));
  EXPECT_DOUBLE_EQ(second.sigma, 0.03) << "the larger spread";
  EXPECT_TRUE(std::isnan(second.stamp)) << "the epoch's";
  EXPECT_EQ(rx.fix(7, {0, 0}, 0.01, 0.01).receiver, 0) << "an unknown id";
  rx.count = 1;
  const Fix alone = rx.fix(1, {0, 0}, 0.01, 0.04);
  EXPECT_EQ(alone.receiver, 0) << "one receiver wired";
  EXPECT_EQ(alone.lever, rx.lever[0]);
  EXPECT_DOUBLE_EQ(alone.sigma, 0.04);
}

// Only the scan mapper's registered poses (update case 2) are offered to the localizer.
TEST(SampleFeed, OnlyRegisteredScanPosesAreTaken) {
  LocalizerParams p;
  p.manager.receivers = 1;
  p.scan_after_s = 0;  // degraded from the start: every pose offered is weighed
  Localizer loc(p);
  loc.speed(20);
  for (int k = 0; k <= 40; ++k) {
    const double t = 0.05 * k;
    loc.imu(t, 0.0, 0.0);
    loc.fixes(t, {Fix{0, {20 * t, 0.0}, p.lever[0], 0.02}});
  }
  ASSERT_TRUE(loc.filter().initialized());
  const double t = 0.05 * 40 - 0.05;  // a frame a sweep ago
  ScanPoseSample registered{t, 2, {20 * t, 0.0}, Eigen::Matrix2d::Identity() * 0.01};
  ScanPoseSample dead_reckoned = registered, none = registered;
  dead_reckoned.update_case = 0;
  none.update_case = 4;
  feed_scan_poses(loc, {dead_reckoned, registered, none});
  EXPECT_EQ(loc.scan_updates() + loc.scan_refused(), 1u);
}

// ModeStatus on a change and at 10 Hz; the first one also tells the run's status line; the time
// from one step to the next counts for the status of the later step.
TEST(ModeCadence, OnAChangeAndAtTenHertz) {
  ModeCadence c;
  ModeDue d = c.step(0.0, Status::normal);
  EXPECT_TRUE(d.publish);
  EXPECT_TRUE(d.announce);
  EXPECT_EQ(d.seq, 0u);
  EXPECT_FALSE(c.step(0.05, Status::normal).publish);
  d = c.step(0.1, Status::normal);
  EXPECT_TRUE(d.publish);
  EXPECT_FALSE(d.announce);
  EXPECT_EQ(d.seq, 1u);
  d = c.step(0.12, Status::warning);
  EXPECT_TRUE(d.publish);
  EXPECT_TRUE(d.announce);
  EXPECT_EQ(d.seq, 2u);
  EXPECT_FALSE(c.step(0.2, Status::warning).publish);
  EXPECT_TRUE(c.step(0.25, Status::emergency).announce);
  EXPECT_DOUBLE_EQ(c.time_in(Status::normal), 0.1);
  EXPECT_NEAR(c.time_in(Status::warning), 0.1, 1e-12);
  EXPECT_NEAR(c.time_in(Status::emergency), 0.05, 1e-12);
}

TEST(EstimatorReport, TheSummarysMetricsInTheirOrder) {
  LocalizerParams p;
  Localizer loc(p);
  ModeCadence modes;
  auto names = [&](Policy policy, bool scan) {
    std::vector<std::string> out;
    for (const auto& [name, value] : summary_metrics(loc, modes, policy, scan, p.selection)) out.push_back(name);
    return out;
  };
  const std::vector<std::string> common = {"epochs",         "fixes_rejected",  "malformed_samples", "fixes_late",
                                           "fixes_too_late", "fix_late_max_s",  "epochs_single",     "epochs_weighted",
                                           "epochs_partial", "epochs_rejected", "time_warning_s",    "time_emergency_s"};
  EXPECT_EQ(names(Policy::naive, false), common);
  std::vector<std::string> gated = common;
  gated.insert(gated.end(), {"scan_updates", "scan_refused"});
  EXPECT_EQ(names(Policy::gated, true), gated);
  std::vector<std::string> resilient = common;
  resilient.insert(resilient.end(), {"reacquisitions", "scan_updates", "scan_refused", "epsilon_m", "delta_m"});
  EXPECT_EQ(names(Policy::resilient, true), resilient);
  const auto m = summary_metrics(loc, modes, Policy::resilient, false, p.selection);
  EXPECT_EQ(m[m.size() - 2].second, p.selection.epsilon);
  EXPECT_EQ(m.back().second, p.selection.delta);
}

// ---- the prior map as a third witness (map_witness.hpp) ----
namespace {

// Fix by fix: a receiver caught lying stays refused (the catch rule has its own test).
WitnessParams witness_on() {
  WitnessParams p;
  p.enabled = true;
  p.retrust_s = 0;
  return p;
}

// A map pose at t: offset from the filter, its covariance (floored as the localizer does) and the
// filter's position spread of 0.1 m beside it.
MapPoseNow map_pose(const MapWitness& w, double t, Eigen::Vector2d offset, Eigen::Matrix2d cov = Eigen::Matrix2d::Identity() * 0.01) {
  const Eigen::Matrix2d floored = w.floored(cov);
  return {t, offset, floored, floored + Eigen::Matrix2d::Identity() * 0.01};
}

}  // namespace

TEST(MapWitness, VerifiedByAgreeingWithAcceptedGnssThenRefusesFixesOffTheMap) {
  const WitnessParams p = witness_on();
  MapWitness w(p);
  const Eigen::Vector2d filter(100, 50);
  const Eigen::Matrix2d rtk = Eigen::Matrix2d::Identity() * 0.02 * 0.02;
  double t = 0;
  for (; t < 1.9; t += 0.1) w.observe(map_pose(w, t, {0.1, -0.05}), true);
  EXPECT_FALSE(w.verified()) << "not yet verify_s of agreement";
  EXPECT_FALSE(w.refuses(t, filter + Eigen::Vector2d(6, -8), rtk, filter)) << "an unverified map refuses nothing";
  for (; t < 2.15; t += 0.1) w.observe(map_pose(w, t, {0.1, -0.05}), true);
  ASSERT_TRUE(w.verified());
  EXPECT_TRUE(w.standing(t));
  // Receivers that moved together by (6, -8) m, claiming RTK: refused; one at the map: not.
  EXPECT_TRUE(w.refuses(t, filter + Eigen::Vector2d(6, -8), rtk, filter));
  EXPECT_FALSE(w.refuses(t, filter + Eigen::Vector2d(0.2, -0.1), rtk, filter));
  // The bound: the map's spread floored at 0.5 m in every direction, chi-square 13.8: 1.86 m.
  EXPECT_FALSE(w.refuses(t, filter + Eigen::Vector2d(0.1 + 1.8, -0.05), rtk, filter));
  EXPECT_TRUE(w.refuses(t, filter + Eigen::Vector2d(0.1 + 1.9, -0.05), rtk, filter));
  EXPECT_EQ(w.refusals(), 2u);
  EXPECT_EQ(w.refusal_stretches(), 1u);
  EXPECT_NEAR(w.first_refusal_s(), t, 1e-12);
  EXPECT_FALSE(w.standing(t + 0.31)) << "a map pose older than fresh_s witnesses nothing";
  // The map's own pose 2.5 m off a filter on healthy GNSS (a registration confidently wrong): the
  // odd one out, it refuses nothing.
  MapWitness odd = w;
  odd.observe(map_pose(odd, t, {2.5, 0.1}), true);
  EXPECT_FALSE(odd.refuses(t, filter, rtk, filter));
  EXPECT_FALSE(w.refuses(t + 0.31, filter + Eigen::Vector2d(6, -8), rtk, filter));
}

// Caught: refused while the map stands or stood within hold_reacquire_s, whatever the map says
// of the fix, until its fixes agree with the filter for retrust_s; with no witness left after
// that, released (the paper's rules judge the fixes again).
TEST(MapWitness, ACaughtReceiverIsRefusedUntilItAgreesOrNoWitnessIsLeft) {
  WitnessParams p = witness_on();
  p.retrust_s = 3.0;
  MapWitness w(p);
  const Eigen::Vector2d filter(0, 0);
  const Eigen::Matrix2d rtk = Eigen::Matrix2d::Identity() * 0.02 * 0.02, sure = Eigen::Matrix2d::Identity() * 0.01;
  double t = 0;
  for (; t < 2.5; t += 0.1) w.observe(map_pose(w, t, {0, 0}), true);
  ASSERT_TRUE(w.refuses(t, {0, 3}, rtk, filter, 1, sure));
  EXPECT_TRUE(w.caught(1));
  EXPECT_FALSE(w.caught(0));
  EXPECT_FALSE(w.refuses(t, {0, 0.1}, rtk, filter, 0, sure)) << "the other receiver is judged as ever";
  // Back at the filter's position: still refused for 3 s of agreement, then taken.
  for (; t < 5.4; t += 0.1) {
    w.observe(map_pose(w, t, {0, 0}), false);
    EXPECT_TRUE(w.refuses(t, {0, 0.1}, rtk, filter, 1, sure)) << t;
  }
  w.observe(map_pose(w, t + 0.1, {0, 0}), false);
  EXPECT_FALSE(w.refuses(t + 0.1, {0, 0.1}, rtk, filter, 1, sure));
  EXPECT_FALSE(w.caught(1));
  // Caught again; then the map silent for more than hold_reacquire_s: released.
  ASSERT_TRUE(w.refuses(t + 0.1, {0, 3}, rtk, filter, 1, sure));
  EXPECT_TRUE(w.refuses(t + 4, {0, 3}, rtk, filter, 1, sure)) << "the map stood 4 s ago: still caught";
  EXPECT_FALSE(w.refuses(t + 6, {0, 3}, rtk, filter, 1, sure)) << "no witness for 6 s";
  EXPECT_FALSE(w.caught(1));
}

TEST(MapWitness, RefusesNothingAlongWhatTheMapCannotTell) {
  const WitnessParams p = witness_on();
  MapWitness w(p);
  // Between parallel walls along x: the map's x spread is 100 m (map_localizer's unseen_sigma).
  Eigen::Matrix2d straight;
  straight << 100.0 * 100.0, 0, 0, 0.01;
  for (double t = 0; t < 2.5; t += 0.1) w.observe(map_pose(w, t, {0, 0}, straight), true);
  ASSERT_TRUE(w.verified());
  const Eigen::Matrix2d rtk = Eigen::Matrix2d::Identity() * 0.02 * 0.02;
  EXPECT_FALSE(w.refuses(2.5, {8, 0}, rtk, {0, 0})) << "8 m along the straight: the map cannot say";
  EXPECT_TRUE(w.refuses(2.5, {0, 3}, rtk, {0, 0})) << "3 m across it: it can";
  // The same straight at 45 degrees: its covariance's diagonal is large both ways, its spread
  // across near zero. The floor holds across it too (a floor on the diagonal alone would not:
  // fixes 7 cm off refused on a clean Spielberg lap).
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(M_PI / 4).toRotationMatrix();
  Eigen::Matrix2d diagonal_straight;
  diagonal_straight << 100.0 * 100.0, 0, 0, 1e-8;
  diagonal_straight = turn * diagonal_straight * turn.transpose();
  const Eigen::Matrix2d floored = with_floor(diagonal_straight, 0.25);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(floored);
  EXPECT_NEAR(es.eigenvalues()(0), 0.0625, 1e-9);
  EXPECT_NEAR(es.eigenvalues()(1), 1e4, 1e-6);
  MapWitness d(p);
  for (double t = 0; t < 2.5; t += 0.1) d.observe(map_pose(d, t, {0, 0}, diagonal_straight), true);
  ASSERT_TRUE(d.verified());
  EXPECT_FALSE(d.refuses(2.5, {0.05, -0.05}, rtk, {0, 0})) << "7 cm across";
  EXPECT_TRUE(d.refuses(2.5, {-2, 2}, rtk, {0, 0})) << "2.8 m across";
  EXPECT_FALSE(d.refuses(2.5, {6, 6}, rtk, {0, 0})) << "8.5 m along";
}

TEST(MapWitness, AJumpOrAGapOffTheFilterLosesTheTrustUntilVerifiedAgain) {
  const WitnessParams p = witness_on();
  MapWitness w(p);
  double t = 0;
  for (; t < 2.5; t += 0.1) w.observe(map_pose(w, t, {0, 0}), true);
  ASSERT_TRUE(w.verified());
  w.observe(map_pose(w, t, {4.0, 0}), true);  // the registration slipped 4 m in one frame (the gate: 2.6 m)
  EXPECT_FALSE(w.verified());
  EXPECT_EQ(w.jumps(), 1u);
  EXPECT_FALSE(w.refuses(t, {6, -8}, Eigen::Matrix2d::Identity() * 4e-4, {0, 0}));
  for (t += 0.1; t < 5.0; t += 0.1) w.observe(map_pose(w, t, {0, 0}), true);
  ASSERT_TRUE(w.verified()) << "back on the filter for verify_s";
  // A gap (LiDAR lost 3 s in a GNSS outage): the next pose is judged on the filter's spread.
  t += 3.0;
  const Eigen::Matrix2d floored = w.floored(Eigen::Matrix2d::Identity() * 0.01);
  w.observe({t, {1.5, 0}, floored, floored + Eigen::Matrix2d::Identity() * 1.0}, false);  // the filter drifted, 1 m spread
  EXPECT_TRUE(w.verified()) << "within the dead-reckoned filter's spread";
  t += 3.0;
  w.observe({t, {9.0, 0}, floored, floored + Eigen::Matrix2d::Identity() * 1.0}, false);
  EXPECT_FALSE(w.verified()) << "9 m off a filter sure to 1 m";
  EXPECT_TRUE(w.holds_reacquisition(t + 1.9)) << "it last stood 3 s before: 5 s of no reacquisition";
  EXPECT_FALSE(w.holds_reacquisition(t + 2.1));
  // Still no GNSS: poses that agree with a filter sure to 0.5 m (dead reckoning, the map unused)
  // verify it again; with the filter unsure (2 m) they could not.
  MapWitness unsure = w;
  for (int k = 1; k <= 21; ++k) {
    w.observe({t + 0.1 * k, {9.0, 0}, floored, floored + Eigen::Matrix2d::Identity() * 0.25}, false);
    unsure.observe({t + 0.1 * k, {9.0, 0}, floored, floored + Eigen::Matrix2d::Identity() * 4.0}, false);
  }
  EXPECT_FALSE(w.verified()) << "9 m off a filter sure to 0.5 m: no agreement";
  for (int k = 22; k <= 45; ++k) {
    w.observe({t + 0.1 * k, {0.2, 0}, floored, floored + Eigen::Matrix2d::Identity() * 0.25}, false);
    unsure.observe({t + 0.1 * k, {0.2, 0}, floored, floored + Eigen::Matrix2d::Identity() * 4.0}, false);
  }
  EXPECT_TRUE(w.verified()) << "2 s on a sure filter";
  EXPECT_FALSE(unsure.verified()) << "a filter unsure to 2 m witnesses nothing";
}

// A map pose that barely tells the along-track direction jitters along it from frame to frame:
// its covariance says so, and that is no jump.
TEST(MapWitness, JitterAlongWhatTheFrameBarelyTellsIsNoJump) {
  const WitnessParams p = witness_on();
  MapWitness w(p);
  Eigen::Matrix2d weak_along_x;
  weak_along_x << 3.0 * 3.0, 0, 0, 0.01;
  double t = 0;
  for (int k = 0; k < 40; ++k, t += 0.1) w.observe(map_pose(w, t, {k % 2 ? 2.5 : -2.5, 0}, weak_along_x), true);
  EXPECT_TRUE(w.verified());
  EXPECT_EQ(w.jumps(), 0u);
  w.observe(map_pose(w, t, {2.5, 3.0}, weak_along_x), true);  // 3 m across: a jump
  EXPECT_EQ(w.jumps(), 1u);
}

TEST(MapWitness, AMapThatNeverAgreesWithGnssIsAMismatch) {
  const WitnessParams p = witness_on();
  MapWitness w(p);
  double t = 0;
  for (; t < 9.9; t += 0.1) w.observe(map_pose(w, t, {30, 4}), true);  // another track's map: located, 30 m off
  EXPECT_FALSE(w.mismatch());
  for (; t < 10.3; t += 0.1) w.unlocated(t, true);  // or not located at all
  EXPECT_TRUE(w.mismatch());
  EXPECT_FALSE(w.ever_verified());
  EXPECT_GT(w.disagreements(), 90u);
  // Later it "locates" near the estimate where it happens to have structure: latched, never trusted.
  for (; t < 14; t += 0.1) w.observe(map_pose(w, t, {0, 0}), true);
  EXPECT_FALSE(w.verified());
  EXPECT_FALSE(w.refuses(t, {6, -8}, Eigen::Matrix2d::Identity() * 4e-4, {0, 0}));
  MapWitness quiet(p);  // GNSS not accepted: nothing to compare with, no verdict
  for (double s = 0; s < 20; s += 0.1) quiet.unlocated(s, false);
  EXPECT_FALSE(quiet.mismatch());
}

namespace {

// A straight drive at 20 m/s on wheels 1 % high, both receivers at 20 Hz (each fix's error
// `fix_error(t)`), map poses at 10 Hz a sweep late (error `map_error(t)`, none while `map_on(t)`
// is false); the filter's final error and the localizer.
struct WitnessDrive {
  std::function<Eigen::Vector2d(double)> fix_error = [](double) { return Eigen::Vector2d::Zero(); };
  std::function<Eigen::Vector2d(double)> fix_error1;  // receiver 1's, when not fix_error
  std::function<bool(double)> gnss_on = [](double) { return true; };
  std::function<Eigen::Vector2d(double)> map_error = [](double) { return Eigen::Vector2d::Zero(); };
  std::function<bool(double)> map_on = [](double) { return true; };
  std::function<double(double)> map_across = [](double) { return 0.1; };  // the map pose's sigma across (y), m
  double seconds = 30, worst_after = 1e9, worst_before = 1e9;  // the largest error between these times
  double worst = 0, emergency_s = 0;

  Localizer run(bool witness, const std::function<void(LocalizerParams&)>& tune = {}) {
    worst = emergency_s = 0;
    LocalizerParams p;
    p.manager.receivers = 2;
    p.manager.witness_timeout_s = 0.3;
    p.roll_filter_s = 0;
    p.witness.enabled = witness;
    if (tune) tune(p);
    Localizer loc(p);
    const double v = 20;
    for (int k = 0; k * 0.01 < seconds; ++k) {
      const double t = 0.01 * k;
      loc.speed(v * 1.01);
      loc.imu(t, 0.0, 0.0);
      if (k % 5 == 0 && gnss_on(t))
        loc.fixes(t, {Fix{0, Eigen::Vector2d(v * t, 0) + fix_error(t), p.lever[0], 0.02},
                      Fix{1, Eigen::Vector2d(v * t, 0) + (fix_error1 ? fix_error1 : fix_error)(t), p.lever[1], 0.02}});
      if (k % 10 == 5 && t > 1) {  // frames between two epochs of fixes
        const double stamp = t - 0.1;
        const Eigen::Matrix2d cov = Eigen::Vector2d(0.01, map_across(stamp) * map_across(stamp)).asDiagonal();
        if (map_on(stamp)) loc.scan_pose(stamp, Eigen::Vector2d(v * stamp, 0) + map_error(stamp), cov);
        else loc.scan_unlocated();
      }
      if (loc.status(t) == Status::emergency && t > 5) emergency_s += 0.01;
      if (t > worst_after && t < worst_before && loc.filter().initialized()) worst = std::max(worst, (loc.filter().position() - Eigen::Vector2d(v * t, 0)).norm());
    }
    return loc;
  }
};

}  // namespace

// Both receivers moved by the same (6, -8) m, claiming RTK-fixed, for 20 s: without the map the
// filter ends on them (they agree with each other; the paper's rule cannot tell); with it every
// biased fix is refused from the first, the map's poses carry the car, and no reacquisition fires.
TEST(Localizer, AMapThatVerifiedRefusesReceiversBiasedTogether) {
  WitnessDrive d;
  d.fix_error = [](double t) { return t >= 10 && t < 30 ? Eigen::Vector2d(6, -8) : Eigen::Vector2d::Zero(); };
  d.worst_after = 5;
  d.run(false);
  EXPECT_GT(d.worst, 5.0) << "without the witness the filter follows the receivers";
  const Localizer loc = d.run(true);
  EXPECT_LT(d.worst, 0.5);
  EXPECT_TRUE(loc.witness().ever_verified());
  EXPECT_NEAR(loc.witness().first_refusal_s(), 10.0, 0.051) << "the bias found at its first epoch";
  EXPECT_EQ(loc.witness().refusal_stretches(), 1u);
  EXPECT_GT(loc.scan_updates(), 150u) << "the map carries the car";
  EXPECT_EQ(loc.reacquisitions(), 0u);
  EXPECT_NE(loc.manager().status(), Status::emergency) << "located on the map";
  EXPECT_EQ(d.emergency_s, 0.0) << "not for a step at the bias's onset either";
}

// One receiver biased: refused by the map as by the paper's rule; the other keeps the filter.
TEST(Localizer, OneBiasedReceiverIsRefusedAndTheOtherKept) {
  WitnessDrive d;
  d.worst_after = 5;
  const Localizer clean = d.run(true);
  EXPECT_EQ(clean.witness().refusals(), 0u) << "no false alarm on a clean drive";
  EXPECT_EQ(clean.scan_updates(), 0u) << "GNSS healthy: the map's poses witness, they do not update";
  // Only receiver 1's fixes wrong, by (3, 4) m from 10 s on.
  LocalizerParams p;
  p.roll_filter_s = 0;
  p.witness.enabled = true;
  Localizer loc(p);
  double worst = 0;
  for (int k = 0; k * 0.01 < 20; ++k) {
    const double t = 0.01 * k;
    loc.speed(20 * 1.01);
    loc.imu(t, 0.0, 0.0);
    const Eigen::Vector2d bias = t >= 10 ? Eigen::Vector2d(3, 4) : Eigen::Vector2d::Zero();
    if (k % 5 == 0) loc.fixes(t, {Fix{0, {20 * t, 0}, p.lever[0], 0.02}, Fix{1, Eigen::Vector2d(20 * t, 0) + bias, p.lever[1], 0.02}});
    if (k % 10 == 0 && t > 1) loc.scan_pose(t - 0.1, {20 * (t - 0.1), 0}, Eigen::Matrix2d::Identity() * 0.01);
    if (t > 5) worst = std::max(worst, (loc.filter().position() - Eigen::Vector2d(20 * t, 0)).norm());
  }
  EXPECT_LT(worst, 0.2);
  EXPECT_GT(loc.witness().refusals(), 150u);
  EXPECT_EQ(loc.scan_updates(), 0u) << "receiver 0 accepted throughout";
}

// One receiver biased for 5 s, then back: caught, it waits out retrust_s beside the healthy one
// (both at the truth then: neither makes the other suspect), and is taken again 3 s after.
TEST(Localizer, ABiasedReceiverBackAtTheTruthIsTakenAgain) {
  WitnessDrive d;
  d.seconds = 25;
  d.fix_error1 = [](double t) { return t >= 10 && t < 15 ? Eigen::Vector2d(3, 4) : Eigen::Vector2d::Zero(); };
  const Localizer loc = d.run(true);
  EXPECT_FALSE(loc.witness().caught(0)) << "the healthy receiver never";
  EXPECT_FALSE(loc.witness().caught(1)) << "released";
  EXPECT_NEAR(loc.witness().last_refusal_s(), 18.0, 0.06) << "3 s of agreement after the bias ended";
  EXPECT_GE(loc.witness().refusals(), 159u) << "receiver 1's 8 s at 20 Hz";
  EXPECT_LE(loc.witness().refusals(), 161u) << "and none of receiver 0's";
}

// A map of another track: never verified, reported, never used; the car stays on GNSS, and in an
// outage dead reckons as it would without a map.
TEST(Localizer, AMapThatDoesNotMatchIsReportedAndNotUsed) {
  WitnessDrive d;
  d.map_error = [](double) { return Eigen::Vector2d(30, 4); };
  d.gnss_on = [](double t) { return t < 20 || t >= 25; };
  d.worst_after = 5;
  const Localizer loc = d.run(true);
  EXPECT_TRUE(loc.witness().mismatch());
  EXPECT_EQ(loc.scan_updates(), 0u);
  EXPECT_GT(loc.scan_unverified(), 0u);
  EXPECT_EQ(loc.witness().refusals(), 0u);
  EXPECT_LT(d.worst, 1.5) << "5 s of dead reckoning on wheels 1 % high, then GNSS again";
}

// Both receivers drifting together from 10 s on at 0.3 m/s across the road, claiming RTK-fixed
// (multipath): the filter follows them, so the map disagrees with both. Once it has disagreed for
// overrule_s past the gate (1.86 m for an RTK filter and the map's 0.5 m floor), the filter is put
// on the map and the drifting fixes are refused from then on. Without the rule the filter ends 6 m
// off.
TEST(Localizer, AMapOverrulesReceiversDriftingTogether) {
  WitnessDrive d;
  d.fix_error = [](double t) { return t >= 10 ? Eigen::Vector2d(0, 0.3 * (t - 10)) : Eigen::Vector2d::Zero(); };
  d.worst_after = 5;
  d.run(true, [](LocalizerParams& p) { p.witness.overrule_s = 0; });
  EXPECT_GT(d.worst, 5.0) << "without the rule the filter follows the receivers";
  const Localizer loc = d.run(true);
  EXPECT_EQ(loc.witness().overrulings(), 1u);
  EXPECT_GT(loc.witness().first_overrule_s(), 15.0) << "not before the drift is past the gate";
  EXPECT_LT(loc.witness().first_overrule_s(), 19.0);
  EXPECT_LT(d.worst, 2.8) << "the drift past the gate, and a second of it";
  d.worst_after = loc.witness().first_overrule_s() + 0.5;
  d.run(true);
  EXPECT_LT(d.worst, 0.5) << "on the map from the overrule on";
  EXPECT_GT(loc.witness().refusals(), 100u) << "the drifting fixes refused";
  EXPECT_EQ(loc.reacquisitions(), 0u);
}

// A receiver the map caught lying stays refused where the map sees little. The drift of the test
// above, overruled; then 4 s where the map's poses tell the car's position across to 3 m only (a
// turn whose one wall is far off): judged by the map's spread alone, the fixes 2 to 3 m across
// would be taken again and pull the filter. Caught, they are refused until they have agreed with
// the filter for retrust_s: once the drift ends, 3 s later.
TEST(Localizer, AReceiverCaughtLyingStaysRefusedWhereTheMapSeesLittle) {
  WitnessDrive d;
  d.seconds = 40;
  d.fix_error = [](double t) { return t >= 10 && t < 30 ? Eigen::Vector2d(0, 0.3 * (t - 10)) : Eigen::Vector2d::Zero(); };
  d.map_across = [](double t) { return t >= 20 && t < 24 ? 3.0 : 0.1; };
  d.worst_after = 20;
  d.worst_before = 30;
  const Localizer before = d.run(true, [](LocalizerParams& p) { p.witness.retrust_s = 0; });
  EXPECT_GE(before.witness().overrulings(), 1u) << "overruled, and again once pulled off";
  EXPECT_GT(d.worst, 2.0) << "without the rule the fixes are taken again where the map is unsure, and pull the filter";
  const Localizer loc = d.run(true);
  const MapWitness& w = loc.witness();
  EXPECT_EQ(w.overrulings(), 1u);
  EXPECT_LT(d.worst, 0.5) << "caught, the drifting fixes are refused throughout";
  EXPECT_FALSE(w.caught(0));
  EXPECT_FALSE(w.caught(1)) << "released once the drift ended";
  EXPECT_GT(w.last_refusal_s(), 32.9) << "agreeing with the filter for 3 s first";
  EXPECT_LT(w.last_refusal_s(), 33.2);
}

// Receivers wrong together are seldom wrong by exactly as much: from 10 s on, receiver 0 is 3 m
// across and receiver 1 1.5 m, inside the map's gate (1.86 m). Judged alone, receiver 1's fixes
// are taken and pull the filter 1.5 m off; beside receiver 0's refused ones, they are refused too.
TEST(Localizer, AFixBesideARefusedOneIsRefusedToo) {
  const auto run = [](bool beside) {
    LocalizerParams p;
    p.manager.receivers = 2;
    p.roll_filter_s = 0;
    p.witness.enabled = true;
    Localizer loc(p);
    double worst = 0;
    for (int k = 0; k * 0.01 < 20; ++k) {
      const double t = 0.01 * k, v = 20;
      loc.speed(v * 1.01);
      loc.imu(t, 0.0, 0.0);
      const Eigen::Vector2d truth(v * t, 0), off = t >= 10 ? Eigen::Vector2d(0, 1) : Eigen::Vector2d::Zero();
      std::vector<Fix> epoch = {Fix{0, truth + 3.0 * off, p.lever[0], 0.02}};
      if (beside || t < 10) epoch.push_back(Fix{1, truth + 1.5 * off, p.lever[1], 0.02});
      if (k % 5 == 0) loc.fixes(t, epoch);
      if (!beside && t >= 10 && k % 5 == 0) loc.fixes(t + 1e-4, {Fix{1, truth + 1.5 * off, p.lever[1], 0.02}});
      if (k % 10 == 5 && t > 1) loc.scan_pose(t - 0.1, {v * (t - 0.1), 0}, Eigen::Matrix2d::Identity() * 0.01);
      if (t > 5) worst = std::max(worst, (loc.filter().position() - truth).norm());
    }
    return std::make_pair(worst, loc.witness());
  };
  const double alone = run(false).first;
  EXPECT_GT(alone, 1.0) << "receiver 1 judged in an epoch of its own: taken, and the filter pulled off";
  const auto [worst, w] = run(true);
  EXPECT_LT(worst, 0.3);
  EXPECT_TRUE(w.caught(0));
  EXPECT_TRUE(w.caught(1));
  EXPECT_NEAR(w.first_refusal_s(), 10.0, 1e-9) << "both at the first epoch";
}

// A map off by 1.5 m for 10 s (a stretch its mapping drive got wrong) with GNSS healthy: under
// the gate, so it never overrules, and no fix is refused.
TEST(Localizer, AMapOffUnderTheGateNeverOverrules) {
  WitnessDrive d;
  d.map_error = [](double t) { return t >= 10 && t < 20 ? Eigen::Vector2d(0, 1.5) : Eigen::Vector2d::Zero(); };
  d.worst_after = 5;
  const Localizer loc = d.run(true);
  EXPECT_EQ(loc.witness().overrulings(), 0u);
  EXPECT_EQ(loc.witness().refusals(), 0u);
  EXPECT_LT(d.worst, 0.2);
}

// A registration that slips (3 m for a second) while GNSS is healthy: the map loses its standing
// at the jump and refuses no good fix; it verifies again once back.
TEST(Localizer, AMapThatSlipsRefusesNoGoodFix) {
  WitnessDrive d;
  d.map_error = [](double t) { return t >= 10 && t < 11 ? Eigen::Vector2d(0, 3) : Eigen::Vector2d::Zero(); };
  d.worst_after = 5;
  const Localizer loc = d.run(true);
  EXPECT_EQ(loc.witness().refusals(), 0u);
  EXPECT_GE(loc.witness().jumps(), 1u);
  EXPECT_TRUE(loc.witness().verified()) << "verified again after the slip";
  EXPECT_LT(d.worst, 0.2);
}
