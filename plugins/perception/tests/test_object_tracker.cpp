// The object tracker (perception/common/object_tracker.hpp) on scripted scenes: the car and others
// driving, detections with noise; each track's position and velocity against the scene's truth.
#include "perception/common/ego_history.hpp"
#include "perception/common/object_tracker.hpp"
#include "perception/common/track_prediction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

using namespace brickyard::perception;

namespace {

struct State {
  double x, y, yaw, speed;
};
// A body `left` m left of a circle of `radius` about (0, radius) (counter-clockwise from the
// origin), `s` m along its own path.
State on_circle(double radius, double s, double speed, double left = 0) {
  const double rho = radius - left, a = s / rho;
  return {rho * std::sin(a), radius - rho * std::cos(a), a, speed};
}

// That circle as a track, a point every metre or so.
brickyard::track::Track circle_track(double radius) {
  brickyard::track::TrackGeometry g;
  const int n = static_cast<int>(2 * M_PI * radius);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    g.line.x.push_back(radius * std::sin(a)), g.line.y.push_back(radius - radius * std::cos(a));
    g.line.width_left.push_back(8), g.line.width_right.push_back(8);
  }
  return brickyard::track::Track(g);
}

// `target` as the car at `ego` sees it (vehicle frame), with noise of sigma m.
Detection seen(const State& ego, const State& target, double sigma, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, sigma);
  const double dx = target.x - ego.x, dy = target.y - ego.y, c = std::cos(ego.yaw), s = std::sin(ego.yaw);
  return {c * dx + s * dy + n(rng), -s * dx + c * dy + n(rng), 4.9, 1.9};
}

// The car and others for `seconds` at 20 Hz; each frame's tracks checked by `check` after `settle_s`.
void drive(ObjectTracker& tracker, double seconds, const std::function<State(double)>& ego, const std::vector<std::function<State(double)>>& others,
           const std::function<void(double, const std::vector<State>&)>& check, double settle_s = 1.0, double sigma = 0.1,
           unsigned seed = 7) {
  std::mt19937 rng(seed);
  for (int k = 0; k <= static_cast<int>(seconds * 20); ++k) {
    const double t = k * 0.05;
    const State e = ego(t);
    std::vector<Detection> d;
    std::vector<State> truth;
    for (const auto& o : others) truth.push_back(o(t)), d.push_back(seen(e, truth.back(), sigma, rng));
    tracker.update(t, {e.x, e.y, e.yaw}, d);
    if (t >= settle_s) check(t, truth);
  }
}

const Track* nearest(const ObjectTracker& tr, const State& s) {
  const Track* best = nullptr;
  for (const Track& t : tr.tracks())
    if (!best || (t.xy - Eigen::Vector2d(s.x, s.y)).norm() < (best->xy - Eigen::Vector2d(s.x, s.y)).norm()) best = &t;
  return best;
}

}  // namespace

// The target: a car 50 m ahead at 90 % of our pace, 2 m left of the centre line, in a
// 400 m turn for 20 s and on a 5 km circle's near-straight: within 0.3 m and 0.5 m/s of the truth
// once settled (1 s), every frame, at five seeds of the detections' noise.
TEST(ObjectTracker, ACarFiftyMetresAheadIsWithinItsTargets) {
  for (const double radius : {400.0, 5000.0}) {
    const auto track = circle_track(radius);
    for (unsigned seed = 1; seed <= 5; ++seed) {
    ObjectTracker tracker(track);
    double worst_pos = 0, worst_speed = 0;
    drive(tracker, 20, [&](double t) { return on_circle(radius, 60 * t, 60); },
          {[&](double t) { return on_circle(radius, 50 + 54 * t, 54, 2.0); }},
          [&](double, const std::vector<State>& truth) {
            const Track* tr = nearest(tracker, truth[0]);
            ASSERT_NE(tr, nullptr);
            EXPECT_TRUE(tr->confirmed);
            worst_pos = std::max(worst_pos, (tr->xy - Eigen::Vector2d(truth[0].x, truth[0].y)).norm());
            worst_speed = std::max(worst_speed, std::abs(tr->speed() - 54.0));
          }, 1.0, 0.1, seed);
    EXPECT_LE(worst_pos, 0.3) << "radius " << radius << ", seed " << seed;
    EXPECT_LE(worst_speed, 0.5) << "radius " << radius << ", seed " << seed;
    EXPECT_EQ(tracker.births(), 1u) << "one car, one track";
    RecordProperty("radius_" + std::to_string(static_cast<int>(radius)) + "_seed_" + std::to_string(seed),
                   "position " + std::to_string(worst_pos) + " m, speed " + std::to_string(worst_speed) + " m/s");
    }
  }
}

// A car 50 m ahead braking at 15 m/s^2 for 2 s from 54 m/s, then powering out at 5 m/s^2 for 6 s
// (the steps in its acceleration the hardest case: no filter foresees them): its track is kept,
// within 0.4 m of it throughout; its speed within 4 m/s in the 1.5 s after each step, within
// 1 m/s after (the acceleration learnt over many frames: docs/tracking.md).
TEST(ObjectTracker, ACarBrakingHardKeepsItsTrack) {
  const auto track = circle_track(400);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    ObjectTracker tracker(track);
    std::mt19937 rng(seed);
    double s = 50, v = 54, worst_pos = 0, worst_settled = 0, worst_step = 0;
    for (int k = 0; k <= 400; ++k) {
      const double t = k * 0.05, a = t >= 8 && t < 10 ? -15.0 : t >= 10 && t < 16 ? 5.0 : 0.0;
      const State e = on_circle(400, 60 * t, 60), o = on_circle(400, s, v, 2.0);
      tracker.update(t, {e.x, e.y, e.yaw}, {seen(e, o, 0.1, rng)});
      const Track* tr = nearest(tracker, o);
      if (t >= 1.0) {
        ASSERT_NE(tr, nullptr);
        worst_pos = std::max(worst_pos, (tr->xy - Eigen::Vector2d(o.x, o.y)).norm());
        const bool settling = (t >= 8 && t < 9.5) || (t >= 10 && t < 11.5) || (t >= 16 && t < 17.5);
        (settling ? worst_step : worst_settled) = std::max(settling ? worst_step : worst_settled, std::abs(tr->speed() - v));
      }
      s += v * 0.05 + a * 0.05 * 0.05 / 2;
      v += a * 0.05;
    }
    EXPECT_LE(worst_pos, 0.4) << "seed " << seed;
    EXPECT_LE(worst_step, 4.0) << "seed " << seed;
    EXPECT_LE(worst_settled, 1.0) << "seed " << seed;
    RecordProperty("seed_" + std::to_string(seed), "position " + std::to_string(worst_pos) + " m, speed " + std::to_string(worst_step) +
                                                     " m/s after a step, " + std::to_string(worst_settled) + " m/s else");
    EXPECT_EQ(tracker.births(), 1u) << "seed " << seed << ": the track was lost";
  }
}

// Two cars side by side, 4 m apart, keep their own tracks; a pylon the car passes stands still.
TEST(ObjectTracker, CarsSideBySideKeepTheirIdsAndAPylonStandsStill) {
  const auto track = circle_track(600);
  ObjectTracker tracker(track);
  std::uint32_t left = 0, right = 0;
  drive(tracker, 4, [](double t) { return on_circle(600, 55 * t, 55); },
        {[](double t) { return on_circle(600, 30 + 50 * t, 50, 2); }, [](double t) { return on_circle(600, 30 + 50 * t, 50, -2); },
         [](double) { return on_circle(600, 150, 0, 6); }},
        [&](double, const std::vector<State>& truth) {
          const Track* a = nearest(tracker, truth[0]);
          const Track* b = nearest(tracker, truth[1]);
          const Track* p = nearest(tracker, truth[2]);
          if (!left) left = a->id, right = b->id;
          EXPECT_EQ(a->id, left);
          EXPECT_EQ(b->id, right);
          EXPECT_LT(p->speed(), 0.5);
        });
  EXPECT_NE(left, right);
  EXPECT_EQ(tracker.tracks().size(), 3u);
}

// A detection seen once (clutter) never confirms and is gone; a car lost coasts max_misses frames,
// then its track dies.
TEST(ObjectTracker, ClutterNeverConfirmsAndALostCarIsDroppedAfterItsMisses) {
  const auto track = circle_track(5000);
  TrackerParams p;
  ObjectTracker tracker(track, p);
  tracker.update(0.0, {}, {{20, 5, 1, 1}});
  EXPECT_FALSE(tracker.tracks().at(0).confirmed);
  for (int k = 1; k <= p.confirm_window; ++k) tracker.update(0.05 * k, {}, {});
  EXPECT_TRUE(tracker.tracks().empty());
  EXPECT_EQ(tracker.deaths(), 1u);

  ObjectTracker lost(track, p);
  double t = 0;
  for (int k = 0; k < 10; ++k, t += 0.05) lost.update(t, {}, {{20 + 2.5 * k, 0, 4.9, 1.9}});
  ASSERT_EQ(lost.tracks().size(), 1u);
  ASSERT_TRUE(lost.tracks()[0].confirmed);
  for (int k = 0; k < p.max_misses; ++k, t += 0.05) lost.update(t, {}, {});
  EXPECT_EQ(lost.tracks().size(), 1u) << "coasting";
  EXPECT_NEAR(lost.tracks()[0].xy.x(), 20 + 2.5 * (9 + p.max_misses), 0.5) << "carried on at its speed";
  lost.update(t, {}, {});
  EXPECT_TRUE(lost.tracks().empty());
}

// The car's pose at a frame's stamp: the latest before it, carried on; none past the gap.
TEST(ObjectTracker, AFrameIsPlacedByThePoseAtItsStamp) {
  EgoHistory h;
  h.add({1'000'000'000, 10, 0, 0, 50, 0});
  h.add({1'010'000'000, 10.5, 0, 0, 50, 0});
  const auto p = h.at(1'030'000'000);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x, 11.5, 1e-9);
  EXPECT_FALSE(h.at(999'000'000).has_value()) << "before every pose";
  EXPECT_FALSE(h.at(1'600'000'000).has_value()) << "past the gap";
}

// A car's path foreseen along the track: at its pace on its line, its spread growing with the
// horizon; braking, it stops rather than backs up; across, it stays on the road; round the start
// line, s wraps.
TEST(ObjectTracker, APathForeseenAlongTheTrack) {
  const auto track = circle_track(400);
  Track car;
  car.state << 100, 2, 50, 0, 0;
  car.cov = Track::Mat::Identity() * 0.01;
  const auto path = predict_along_track(car, track);
  ASSERT_EQ(path.size(), 30u);
  EXPECT_NEAR(path.back().t, 3.0, 1e-9);
  EXPECT_NEAR(path.back().s, 250, 1e-6);
  EXPECT_NEAR(path.back().d, 2, 1e-9);
  const State truth = on_circle(400, 250.0 * (400 - 2) / 400, 50, 2);  // s is the centre line's
  EXPECT_NEAR(path.back().x, truth.x, 0.05);
  EXPECT_NEAR(path.back().y, truth.y, 0.05);
  for (std::size_t k = 1; k < path.size(); ++k) EXPECT_GT(path[k].sigma_s, path[k - 1].sigma_s);
  EXPECT_GT(path.back().sigma_s, 5.0) << "3 s ahead a car may have braked";

  car.state << 100, 2, 10, 6, -15;  // braking hard at 10 m/s, moving over at 6 m/s
  const auto stop = predict_along_track(car, track);
  for (const auto& q : stop) EXPECT_GE(q.speed, 0.0);
  EXPECT_LT(stop.back().s, 100 + 10 * 3.0) << "slower than at its pace";
  EXPECT_LE(stop.back().d, 8.0) << "on the road (8 m each side)";

  car.state << track.length() - 20, 0, 50, 0, 0;
  const auto round = predict_along_track(car, track);
  EXPECT_NEAR(round.back().s, 130, 1e-6);
}

// A wall's stripes at the road's edge, or just inside it (within road_margin), slide along as the
// car drives (a grazing LiDAR's columns land further on each frame): never followed, each counted
// as off the road; a car on the road beside them is.
TEST(ObjectTracker, StripesAtTheRoadsEdgeAreNeverFollowed) {
  const auto track = circle_track(600);
  ObjectTracker tracker(track);
  std::mt19937 rng(3);
  std::size_t frames = 0;
  for (int k = 0; k <= 80; ++k, ++frames) {
    const double t = k * 0.05;
    const State e = on_circle(600, 55 * t, 55), car = on_circle(600, 40 + 50 * t, 50, 1);
    std::vector<Detection> d{seen(e, car, 0.1, rng)};
    for (double left : {8.3, 7.8, -7.7}) {  // the edges at +-8 m
      Detection stripe = seen(e, on_circle(600, 120 + 40 * t, 0, left), 0.02, rng);
      stripe.size_x = 0.03, stripe.size_y = 0.0;
      d.push_back(stripe);
    }
    tracker.update(t, {e.x, e.y, e.yaw}, d);
  }
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_LT((tracker.tracks()[0].xy - Eigen::Vector2d(on_circle(600, 40 + 50 * 4.0, 50, 1).x, on_circle(600, 40 + 50 * 4.0, 50, 1).y)).norm(), 0.5);
  EXPECT_EQ(tracker.off_road(), 3 * frames);
}
