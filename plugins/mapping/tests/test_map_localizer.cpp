// Localization on a prior map (map_localizer.hpp, map_localization_run.hpp): the map as the
// scan mapper writes it, frames located on it from a guess that is off, what the map cannot tell
// said in the covariance, and frames it cannot locate counted by why.
#include "mapping/common/map_localization_run.hpp"
#include "mapping/common/map_localizer.hpp"
#include "mapping/common/pcd.hpp"
#include "mapping/common/scan_mapper.hpp"
#include "scenes.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace brickyard::mapping;
using namespace brickyard::mapping::scenes;

namespace {

// A scene's map as the mapping drive leaves it: stacked by the scan mapper, written as a PCD
// file (its fine voxels' means) and read back.
Points map_file_of(const Points& scene, const std::string& name) {
  ScanMapper mapper;
  mapper.add(scene, Eigen::Isometry3d::Identity(), Eigen::Matrix<double, 6, 6>::Zero());
  const std::string path = ::testing::TempDir() + name + ".pcd";
  write_pcd(path, mapper.fine_map());
  Points map = read_pcd(path);
  std::remove(path.c_str());
  return map;
}

Eigen::Matrix3d planar_of(const Located& r) { return planar_covariance(r.covariance); }

// The scenes are a few tens of metres across, sampled every 0.2 m: their frames are thinned at
// 0.4 m, as a track's 100 m of LiDAR returns are at the default 0.8 m.
MapLocalizerParams scene_params() {
  MapLocalizerParams p;
  p.scan_voxel = 0.4f;
  return p;
}

}  // namespace

// In the yard (walls and boxes tell every direction) a frame is located from a guess 0.7 m and
// 2 degrees off to within centimetres, and its covariance is the registration's: small, and no
// smaller than min_sigma in any direction.
TEST(MapLocalizer, LocatesAFrameFromAGuessThatIsOff) {
  const MapLocalizer loc(map_file_of(yard(0.15, 0.01, 1), "yard"), scene_params());
  const Eigen::Isometry3d truth = planar(2.0, 0.5, 3.0);
  const Points frame = moved(yard(0.2, 0.01, 2), truth.inverse());
  const Located r = loc.locate(frame, planar(2.6, 0.1, 1.0));
  ASSERT_TRUE(r.registered) << failure_name(r.failure);
  EXPECT_EQ(r.failure, LocateFailure::none);
  EXPECT_NEAR(r.pose.translation().x(), 2.0, 0.03);
  EXPECT_NEAR(r.pose.translation().y(), 0.5, 0.03);
  EXPECT_NEAR(yaw_of(r.pose) * 180 / M_PI, 3.0, 0.1);
  EXPECT_EQ(r.unseen, 0);
  EXPECT_NEAR(r.correction, std::hypot(0.6, 0.4), 0.05);
  const Eigen::Matrix3d c = planar_of(r);
  EXPECT_LT(c(0, 0), 0.2 * 0.2);
  EXPECT_LT(c(1, 1), 0.2 * 0.2);
  const double floor = loc.params().min_sigma * loc.params().min_sigma;
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(c.topLeftCorner<2, 2>()).eigenvalues().minCoeff(), floor * (1 - 1e-9));
}

// The pose is the frame's own, not leaned toward the guess by the weak prior: with the prior made
// strong (1 cm, 1 mrad: as strong as the frame is where it tells little, along a smooth wall),
// the registration stops at a guess 0.1 m off (its steps, held back by the prior, shorter than
// 5 mm at once), while the covariance says the frame's spread alone. The frame's own step from
// there brings the pose within 3 cm of the truth (it stayed 0.1 m off before).
TEST(MapLocalizer, APoseIsTheFramesNotLeanedTowardTheGuess) {
  MapLocalizerParams p = scene_params();
  p.prior_sigma = 0.01;
  p.prior_sigma_turn = 0.001;
  const MapLocalizer loc(map_file_of(yard(0.15, 0.01, 1), "yard_lean"), p);
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 3.0).inverse());
  const Located r = loc.locate(frame, planar(2.1, 0.5, 3.0));
  ASSERT_TRUE(r.registered) << failure_name(r.failure);
  EXPECT_NEAR(r.pose.translation().x(), 2.0, 0.03);
  EXPECT_NEAR(r.pose.translation().y(), 0.5, 0.03);
}

// The map prepared on two threads (its surfaces, its two voxel maps side by side) locates a frame
// exactly as on one.
TEST(MapLocalizer, AMapPreparedOnTwoThreadsLocatesAsOnOne) {
  const Points map = map_file_of(yard(0.15, 0.01, 1), "yard_threads");
  MapLocalizerParams p1 = scene_params(), p2 = scene_params();
  p1.threads = 1, p2.threads = 2;
  const MapLocalizer one(map, p1), two(map, p2);
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 3.0).inverse());
  const Located a = one.locate(frame, planar(2.6, 0.1, 1.0)), b = two.locate(frame, planar(2.6, 0.1, 1.0));
  ASSERT_TRUE(a.registered) << failure_name(a.failure);
  EXPECT_EQ(a.pose.matrix(), b.pose.matrix());
  EXPECT_EQ(a.covariance, b.covariance);
  EXPECT_EQ(a.matched, b.matched);
}

// A guess 3.4 m too high (the height carried from the last frame where the mapping drive closed
// its loop, its map's height drifted): the height is found on the map first, then the frame is
// located as from the right height. Without the search it matches nothing.
TEST(MapLocalizer, FindsTheFramesHeightOnTheMapFirst) {
  const Points map = map_file_of(yard(0.15, 0.01, 1), "yard_height");
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 3.0).inverse());
  Eigen::Isometry3d guess = planar(2.3, 0.3, 2.0);
  guess.translation().z() = 3.4;
  const Located r = MapLocalizer(map, scene_params()).locate(frame, guess);
  ASSERT_TRUE(r.registered) << failure_name(r.failure);
  EXPECT_NEAR(r.pose.translation().x(), 2.0, 0.03);
  EXPECT_NEAR(r.pose.translation().z(), 0.0, 0.05);
  MapLocalizerParams fixed = scene_params();
  fixed.height_search = 0;
  EXPECT_FALSE(MapLocalizer(map, fixed).locate(frame, guess).registered);
}

// Between two smooth walls the map tells where the car is across and how it is turned, not how
// far along: there the pose is the guess's and the covariance says unseen_sigma, never a
// confident coordinate the frame does not support.
TEST(MapLocalizer, SaysWhatTheMapCannotTellAlongACorridor) {
  const MapLocalizer loc(map_file_of(corridor(0.15, 1), "corridor"), scene_params());
  const Points frame = moved(corridor(0.2, 2), planar(2.0, 0.0, 0.0).inverse());
  const Located r = loc.locate(frame, planar(2.4, 0.3, 1.0));
  ASSERT_TRUE(r.registered) << failure_name(r.failure);
  EXPECT_GE(r.unseen, 1);
  EXPECT_NEAR(r.pose.translation().y(), 0.0, 0.03);
  EXPECT_NEAR(yaw_of(r.pose) * 180 / M_PI, 0.0, 0.1);
  EXPECT_NEAR(r.pose.translation().x(), 2.4, 0.01) << "along the corridor: the guess's";
  const Eigen::Matrix3d c = planar_of(r);
  const double unseen = loc.params().unseen_sigma * loc.params().unseen_sigma;
  EXPECT_GT(c(0, 0), 0.9 * unseen);
  EXPECT_LT(c(1, 1), 0.2 * 0.2);
}

// A right-hand bend with its outer wall only (radius 56 m about (0, -50), the car at the origin
// heading +x), its road flat, or in a map rising `ramp` per metre across the road toward the wall
// from 4.5 m right of the car: the sheet a mapping drive whose roll drifted leaves.
Points bend(double step, double ramp, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 0.01f);
  Points pts;
  const Eigen::Vector2d centre(0, -50);
  for (double a = -0.7; a <= 0.7; a += step / 56) {
    const Eigen::Vector2d out(std::sin(a), std::cos(a));
    for (double r = 44; r <= 56; r += step) {
      const Eigen::Vector2d q = centre + r * out;
      pts.emplace_back(q.x() + n(rng), q.y() + n(rng), ramp * std::max(0.0, r - 45.5) + n(rng));
    }
    const Eigen::Vector2d w = centre + 56.0 * out;
    for (double z = 0; z <= 1.2; z += step) pts.emplace_back(w.x() + n(rng), w.y() + n(rng), 10.5 * ramp + z + n(rng));
  }
  return pts;
}

// The map's road tilted 17 % across where the frame's is level (Spielberg's hairpin in an
// outer-wall map): the road is made level on both sides and only the wall says where the car is,
// so the pose stays within centimetres of the truth. Kept as it is, the frame's road slides down
// the map's sheet, the pose metres off across the road.
TEST(MapLocalizer, AMapsTiltedRoadDoesNotSlideThePose) {
  const Points map = map_file_of(bend(0.15, 0.17, 1), "tilted_bend");
  const Points frame = bend(0.2, 0.0, 2);
  MapLocalizerParams kept = scene_params();
  kept.ground_tilt = 0;
  kept.max_correction = 10;
  const Located level = MapLocalizer(map, scene_params()).locate(frame, Eigen::Isometry3d::Identity());
  const Located slid = MapLocalizer(map, kept).locate(frame, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(level.registered) << failure_name(level.failure);
  EXPECT_NEAR(level.pose.translation().y(), 0.0, 0.1);
  EXPECT_NEAR(level.pose.translation().x(), 0.0, 0.1);
  ASSERT_TRUE(slid.registered) << failure_name(slid.failure);
  EXPECT_GT(slid.pose.translation().head<2>().norm(), 0.5) << "without levelling the road the test would not tell";
}

// A map of somewhere else (the yard 500 m away: another track's) locates nothing; an empty frame
// neither. Each is counted by why, and the pose is the guess.
TEST(MapLocalizer, AMapOfElsewhereOrAnEmptyFrameLocatesNothing) {
  const MapLocalizer loc(moved(map_file_of(yard(0.15, 0.01, 1), "far"), planar(500, 0, 0)), scene_params());
  const Points frame = yard(0.2, 0.01, 2);
  const Located r = loc.locate(frame, Eigen::Isometry3d::Identity());
  EXPECT_FALSE(r.registered);
  EXPECT_TRUE(r.failure == LocateFailure::too_few_matched || r.failure == LocateFailure::not_converged) << failure_name(r.failure);
  EXPECT_TRUE(r.pose.isApprox(Eigen::Isometry3d::Identity()));
  const Located none = loc.locate({}, Eigen::Isometry3d::Identity());
  EXPECT_EQ(none.failure, LocateFailure::too_few_points);
}

// A guess farther off than max_correction is not corrected (a frame that "locates" 5 m away is
// more likely a wrong match than a right one): implausible, the guess kept.
TEST(MapLocalizer, ACorrectionBeyondTheBoundIsRefused) {
  MapLocalizerParams p = scene_params();
  p.max_correction = 0.3;
  const MapLocalizer loc(map_file_of(yard(0.15, 0.01, 1), "yard_bound"), p);
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 0).inverse());
  const Located r = loc.locate(frame, planar(2.6, 0.1, 0));
  EXPECT_FALSE(r.registered);
  EXPECT_EQ(r.failure, LocateFailure::implausible);
}

// Over a drive: each frame from the estimate at its stamp; without one near it, left out and
// counted; the height, roll and pitch found carried to the next frame's guess; the summary.
TEST(MapLocalizationRun, FramesFromTheEstimateAtTheirStampAndTheSummary) {
  MapLocalizationRunParams scene;
  scene.localizer = scene_params();
  MapLocalizationRun run(map_file_of(yard(0.15, 0.01, 1), "run"), scene);
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 3.0).inverse());
  EXPECT_FALSE(run.frame(1'000'000'000, frame)) << "no estimate yet";
  EstimateExtras extras;
  extras.covariance = {0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.01};
  run.estimate(1'000'000'000, {2.3, 0.2, 1.0 * M_PI / 180}, extras);
  run.estimate(1'100'000'000, {2.5, 0.4, 1.0 * M_PI / 180}, extras);
  const auto f = run.frame(1'050'000'000, frame);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->update_case, 2);
  EXPECT_NEAR(f->x, 2.0, 0.03);
  EXPECT_NEAR(f->y, 0.5, 0.03);
  EXPECT_LT(f->covariance[0], 0.25 / 10) << "the map's, far below the estimate's";
  EXPECT_FALSE(run.frame(2'000'000'000, frame)) << "the estimate 0.9 s away";
  std::map<std::string, double> m;
  for (const auto& [name, value] : run.metrics()) m[name] = value;
  EXPECT_EQ(m["frames"], 1);
  EXPECT_EQ(m["located"], 1);
  EXPECT_EQ(m["frames_without_estimate"], 2);
  EXPECT_GT(m["map_points"], 1000);
  EXPECT_NEAR(m["correction_max_m"], std::hypot(0.4, 0.2), 0.05);
  EXPECT_EQ(m["frames_skipped"], 0);
}

// min_interval_s: a frame within it of the last one tried is left out and counted; while the
// estimate is NORMAL (GNSS taken, the map a witness), within normal_interval_s; the first frame
// after it leaves NORMAL is located at once.
TEST(MapLocalizationRun, FramesWithinTheIntervalAreLeftOut) {
  MapLocalizationRunParams p;
  p.localizer = scene_params();
  p.min_interval_s = 0.1;
  p.normal_interval_s = 0.3;
  MapLocalizationRun run(map_file_of(yard(0.15, 0.01, 1), "run_interval"), p);
  const Points frame = moved(yard(0.2, 0.01, 2), planar(2.0, 0.5, 3.0).inverse());
  EstimateExtras extras;
  extras.covariance = {0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.01};
  auto ms = [](int t) { return std::int64_t{t} * 1'000'000; };
  for (int t = 1000; t <= 1800; t += 50) {
    extras.status = t < 1500 ? 0 : 1;  // NORMAL, then WARNING from 1.5 s
    run.estimate(ms(t), {2.1, 0.5, 3.0 * M_PI / 180}, extras);
  }
  std::vector<int> located;
  for (int t = 1000; t <= 1800; t += 50)
    if (run.frame(ms(t), frame)) located.push_back(t);
  EXPECT_EQ(located, (std::vector<int>{1000, 1300, 1500, 1600, 1700, 1800}))
      << "NORMAL: every 0.3 s; WARNING: at once, then every 0.1 s";
  std::map<std::string, double> m;
  for (const auto& [name, value] : run.metrics()) m[name] = value;
  EXPECT_EQ(m["frames_skipped"], 17 - 6);
  EXPECT_EQ(m["frames"], 6);
}
