// Perception algorithms on synthetic clouds with known answers.
#include "perception/common/clustering.hpp"
#include "perception/common/deskew.hpp"
#include "perception/common/frame_set.hpp"
#include "perception/common/ground_filter.hpp"
#include "perception/common/obstacles.hpp"
#include "perception/common/packed_keys.hpp"
#include "perception/common/stamp_match.hpp"
#include "perception/common/wall_fit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

using namespace brickyard::perception;

namespace {

// A road surface banked by `bank_deg` across y (rising to -y, the outside of a left turn), 40 x
// 16 m, sampled every 5 cm along rings like a LiDAR's; a 1.2 m wall at y = -9 standing on the
// road's edge height; a pylon (r 0.2 m, 0.7 m high) on the road at (25, 2).
struct Scene {
  Points points;
  std::vector<int> truth;  // 0 road, 1 wall, 2 pylon
};

Scene banked_scene(double bank_deg) {
  Scene s;
  const double tb = std::tan(bank_deg * M_PI / 180);
  auto road_z = [&](double y) { return static_cast<float>(-std::max(-9.0, std::min(7.0, y)) * tb); };
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0, 0.02f);
  for (double x = 2; x < 42; x += 0.25)
    for (double y = -8.9; y < 7; y += 0.25) {
      s.points.emplace_back(x, y, road_z(y) + noise(rng));
      s.truth.push_back(0);
    }
  for (double x = 2; x < 42; x += 0.1)
    for (double z = 0.05; z < 1.2; z += 0.1) {
      s.points.emplace_back(x, -9.0f + noise(rng), road_z(-9) + z);
      s.truth.push_back(1);
    }
  for (double a = 0; a < M_PI; a += 0.1)
    for (double z = 0.05; z < 0.7; z += 0.05) {
      s.points.emplace_back(25 - 0.2 * std::sin(a), 2 + 0.2 * std::cos(a), road_z(2) + z);
      s.truth.push_back(2);
    }
  return s;
}

}  // namespace

TEST(GroundFilter, VoxelCentroidsInFirstMetOrder) {
  Points in = {{0.01f, 0.01f, 0.01f}, {0.5f, 0, 0}, {0.03f, 0.05f, 0.07f}};
  Points v = voxel_filter(in, 0.2f);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_TRUE(v[0].isApprox(Point(0.02f, 0.03f, 0.04f)));
  EXPECT_TRUE(v[1].isApprox(Point(0.5f, 0, 0)));
}

// The banked road is ground and the wall and the pylon are not, at 9.2 deg (IMS) and 20 deg
// (Las Vegas) alike: nothing depends on the road's slope.
TEST(GroundFilter, BankedRoadIsGroundWallAndPylonAreNot) {
  for (double bank : {0.0, 9.2, 20.0}) {
    Scene s = banked_scene(bank);
    GroundFilter f;
    GroundResult r;
    f.run(s.points, r);
    std::size_t tp = 0, fp = 0, fn = 0;
    // Ground truth per voxel from its centroid: road if it lies on the road surface.
    const double tb = std::tan(bank * M_PI / 180);
    for (std::size_t v = 0; v < r.voxels.size(); ++v) {
      const Point& c = r.voxels[v];
      const double rz = -std::max(-9.0, std::min(7.0, static_cast<double>(c.y()))) * tb;
      // Road: on the surface, away from the wall's and the pylon's foot; standing: 0.2 m or
      // more above it. A voxel at a foot mixes both and is not scored.
      const bool at_foot = c.y() < -8.8f || std::hypot(c.x() - 25, c.y() - 2) < 0.45;
      const bool is_road = !at_foot && std::abs(c.z() - rz) < 0.1, standing = c.z() - rz >= 0.2;
      if (!is_road && !standing) continue;
      if (r.ground[v] && is_road) ++tp;
      if (r.ground[v] && standing) ++fp;
      if (!r.ground[v] && is_road) ++fn;
    }
    const double precision = static_cast<double>(tp) / (tp + fp), recall = static_cast<double>(tp) / (tp + fn);
    EXPECT_GE(precision, 0.98) << "bank " << bank;
    EXPECT_GE(recall, 0.98) << "bank " << bank;
    // The pylon survives as a vertical feature.
    int pylon = 0;
    for (const Point& p : r.obstacles()) pylon += std::hypot(p.x() - 25, p.y() - 2) < 0.5;
    EXPECT_GE(pylon, 3) << "bank " << bank;
  }
}

TEST(Clustering, TwoBlobsAndANoisePointAndTheSizeLimits) {
  Points p;
  for (int i = 0; i < 10; ++i) p.emplace_back(0.1f * i, 0, 0);         // a 0.9 m line: one cluster
  for (int i = 0; i < 5; ++i) p.emplace_back(5 + 0.1f * i, 0, 0);      // another, 5 points
  p.emplace_back(10, 10, 10);                                          // alone
  for (int i = 0; i < 3; ++i) p.emplace_back(0.05f + 0.1f * i, 0.3f, 0);  // joins the first (0.3 m away)
  EuclideanClustering c({0.35f, 2, 100});
  std::vector<std::vector<int>> out;
  c.run(p, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].size(), 13u);
  EXPECT_EQ(out[0].front(), 0);
  EXPECT_EQ(out[1], (std::vector<int>{10, 11, 12, 13, 14}));
  // A component above max_size is dropped, not split.
  EuclideanClustering small({0.35f, 2, 12});
  small.run(p, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].size(), 5u);
}

// A wall y = -8 + 0.01 x + 0.002 x^2 leaning by k (a rolled car) is fitted at z = 0: the
// distance, heading and curvature come back, the lean too; without the lean term the distance
// is off by k times the wall returns' mean height.
TEST(WallFit, QuadraticWallWithLeanIsRecovered) {
  const double c0 = -8, c1 = 0.01, c2 = 0.002, k = 0.162;
  Points p;
  std::vector<std::vector<int>> clusters(3);
  for (double x = -5; x < 60; x += 0.3)
    for (double z = 0.3; z < 1.2; z += 0.2) {
      clusters[1].push_back(static_cast<int>(p.size()));
      p.emplace_back(x, c0 + c1 * x + c2 * x * x + k * z, z);
    }
  for (int i = 0; i < 40; ++i) {  // a longer structure on the left: not the right wall
    clusters[0].push_back(static_cast<int>(p.size()));
    p.emplace_back(-10 + 2.0f * i, 9, 0.5f);
  }
  for (int i = 0; i < 5; ++i) {  // a small object on the right
    clusters[2].push_back(static_cast<int>(p.size()));
    p.emplace_back(30, -3, 0.1f * i);
  }
  WallParams wp;
  const WallFit w = fit_wall(p, clusters, wp);
  ASSERT_TRUE(w.valid);
  EXPECT_EQ(w.cluster, 1);
  EXPECT_NEAR(w.distance, c0, 1e-6);
  EXPECT_NEAR(w.lean, k, 1e-6);
  ASSERT_EQ(w.coefficients.size(), 3u);
  EXPECT_NEAR(w.coefficients[1], c1, 1e-8);
  EXPECT_NEAR(w.coefficients[2], c2, 1e-9);
  const double d1 = c1 + 2 * c2 * wp.lookahead;
  EXPECT_NEAR(w.heading, std::atan(d1), 1e-8);
  EXPECT_NEAR(w.curvature, 2 * c2 / std::pow(1 + d1 * d1, 1.5), 1e-8);
  EXPECT_LT(w.residual, 1e-5);
  EXPECT_NEAR(poly_value(w.coefficients, 20.0), c0 + c1 * 20 + c2 * 400, 1e-6);
  wp.lean = false;
  EXPECT_NEAR(fit_wall(p, clusters, wp).distance - c0, k * 0.7, 0.02);
  // The left side finds the left structure.
  wp.side = 1;
  EXPECT_EQ(fit_wall(p, clusters, wp).cluster, 0);
}

TEST(WallFit, TooFewOrTooShortIsNotValid) {
  Points p;
  std::vector<std::vector<int>> clusters(1);
  for (int i = 0; i < 50; ++i) {
    clusters[0].push_back(i);
    p.emplace_back(0.05f * i, -5, 0.02f * (i % 10));  // 2.5 m long
  }
  WallParams wp;
  WallFit w = fit_wall(p, clusters, wp);
  EXPECT_EQ(w.cluster, 0);
  EXPECT_FALSE(w.valid);
  wp.min_length = 2;
  EXPECT_TRUE(fit_wall(p, clusters, wp).valid);
  wp.min_points = 51;
  EXPECT_FALSE(fit_wall(p, clusters, wp).valid);
  EXPECT_EQ(fit_wall(p, {}, wp).cluster, -1);
}

// The car stands at a chicane's exit (Monza, s = 982 m, as eval_tracks found it): the wall beside
// it is 10 m long, a straight stretch of the same wall seen 75-95 m behind is 20 m long. The
// wall is the one beside the car, not the longer one the fit window (fit_behind) leaves out.
TEST(WallFit, TheWallBesideTheCarNotALongerOneFarBehind) {
  Points p;
  std::vector<std::vector<int>> clusters(2);
  for (double x = -94; x <= -74; x += 0.2) {
    clusters[0].push_back(static_cast<int>(p.size()));
    p.emplace_back(x, 22, 0.5f);
  }
  for (double x = -4; x <= 6; x += 0.1) {
    clusters[1].push_back(static_cast<int>(p.size()));
    p.emplace_back(x, 4.8 + 0.02 * x * x, 0.5f);
  }
  WallParams wp;
  wp.side = 1;
  wp.fit_behind = 5;
  const WallFit w = fit_wall(p, clusters, wp);
  EXPECT_EQ(w.cluster, 1);
  ASSERT_TRUE(w.valid);
  EXPECT_NEAR(w.distance, 4.8, 0.05);
  // Where no cluster reaches the window, the longest is still the one to grow from.
  wp.fit_behind = 1;
  wp.fit_range = 2;
  Points far = {p.begin(), p.begin() + static_cast<long>(clusters[0].size())};
  EXPECT_EQ(fit_wall(far, {clusters[0]}, wp).cluster, 0);
}

namespace {
// One cluster of these points, appended to the cloud.
void add_cluster(Points& p, std::vector<std::vector<int>>& clusters, std::initializer_list<Point> q) {
  clusters.emplace_back();
  for (const Point& x : q) {
    clusters.back().push_back(static_cast<int>(p.size()));
    p.push_back(x);
  }
}
}  // namespace

// A pylon on the road is an obstacle; the wall, a cluster hugging it, and things beyond it or
// outside the corridor are not.
TEST(Obstacles, InsideTheCorridorAndNotWall) {
  Points p;
  std::vector<std::vector<int>> clusters;
  auto add = [&](std::initializer_list<Point> q) { add_cluster(p, clusters, q); };
  add({{40, 1, 0.1f}, {40.2f, 1.2f, 0.4f}, {40.1f, 0.9f, 0.6f}});   // pylon: obstacle
  add({{20, -7.8f, 0.2f}, {21, -7.8f, 0.5f}, {22, -7.7f, 0.3f}});  // on the right wall's face
  add({{30, -12, 0.2f}, {30, -12, 0.5f}, {30.2f, -12, 0.3f}});     // beyond the right wall
  add({{50, 20, 0.2f}, {50, 20, 0.5f}, {50.2f, 20, 0.3f}});        // outside the corridor
  add({{0, 6, 0.2f}, {12, 6, 0.5f}, {6, 6, 0.3f}});                // 12 m long: structure
  add({{150, -3, 0.2f}, {150, -3, 0.5f}, {150.1f, -3, 0.3f}});     // far beyond the fit: tangent line
  WallFit right;
  right.coefficients = {-8, 0, 0};
  right.x_min = -5;
  right.x_max = 100;
  right.valid = true;
  const auto obstacles = find_obstacles(p, clusters, {{right, -1}}, ObstacleParams{});
  ASSERT_EQ(obstacles.size(), 2u);
  EXPECT_NEAR(obstacles[0].centroid.x(), 40.1f, 1e-4);
  EXPECT_EQ(obstacles[0].points, 3u);
  EXPECT_NEAR(obstacles[0].size.y(), 0.3f, 1e-5);
  EXPECT_NEAR(obstacles[1].centroid.x(), 150.033f, 1e-3);
  // Without a wall fit, the clusters on and beyond the wall are inside the 15 m corridor.
  EXPECT_EQ(find_obstacles(p, clusters, {}, ObstacleParams{}).size(), 4u);
  // A fit that is not valid cuts nothing.
  right.valid = false;
  EXPECT_EQ(find_obstacles(p, clusters, {{right, -1}}, ObstacleParams{}).size(), 4u);
}

// Far past where a wall is known, its line is a guess: only what lies within wall_depth beyond
// it is wall. A pylon seen 186 m ahead where a straight bends lay 3 m "beyond" the guessed line;
// the LiDAR does not see through walls, so it is not wall.
TEST(Obstacles, FarPastAFittedWallOnlyItsLineIsWall) {
  Points p;
  std::vector<std::vector<int>> clusters;
  auto add = [&](std::initializer_list<Point> q) { add_cluster(p, clusters, q); };
  add({{186, 9, 0.1f}, {186.2f, 9.1f, 0.4f}, {186.1f, 8.9f, 0.6f}});   // 3 m beyond the left wall's line: obstacle
  add({{180, 6.5f, 0.2f}, {181, 6.6f, 0.5f}, {182, 6.5f, 0.3f}});      // 0.5 m beyond it: wall
  add({{40, 7.5f, 0.2f}, {40.2f, 7.5f, 0.5f}, {40.1f, 7.5f, 0.3f}});   // 1.5 m beyond where it is known: wall
  WallFit left;
  left.coefficients = {6, 0, 0};
  left.x_min = -5;
  left.x_max = 20;
  left.valid = true;
  const auto obstacles = find_obstacles(p, clusters, {{left, +1}}, ObstacleParams{});
  ASSERT_EQ(obstacles.size(), 1u);
  EXPECT_NEAR(obstacles[0].centroid.x(), 186.1f, 1e-3);
  // Trusting the guess all the way (the old rule) took the pylon for wall.
  ObstacleParams trusting;
  trusting.wall_reach = 1e6;
  EXPECT_TRUE(find_obstacles(p, clusters, {{left, +1}}, trusting).empty());
}

TEST(FrameSet, CompleteSetsAndALostFrame) {
  FrameSet<int> sets(3, 25'000'000);
  EXPECT_TRUE(sets.offer(0, 100'000'000, 10).empty());
  EXPECT_TRUE(sets.offer(2, 101'000'000, 12).empty());
  auto done = sets.offer(1, 100'000'000, 11);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0], (std::vector<int>{10, 11, 12}));  // in sensor order
  // Sensor 1 loses its frame: the next frame's first cloud closes the set as it is.
  EXPECT_TRUE(sets.offer(0, 150'000'000, 20).empty());
  EXPECT_TRUE(sets.offer(2, 150'000'000, 22).empty());
  done = sets.offer(0, 200'000'000, 30);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0], (std::vector<int>{20, 22}));
  EXPECT_EQ(sets.partial(), 1u);
  // One sensor alone completes every set at once.
  FrameSet<int> one(1, 25'000'000);
  EXPECT_EQ(one.offer(0, 0, 1).size(), 1u);
}

TEST(FrameSet, SensorPoseMovesPointsIntoTheVehicleFrame) {
  SensorPose pose{1.5, 0.3, 0.5, 0, 0, M_PI / 2};  // facing left
  const float x[] = {10, NAN}, y[] = {0, 0}, z[] = {1, 0};
  Points out;
  append_in_vehicle_frame(pose, x, y, z, 2, out);
  ASSERT_EQ(out.size(), 1u);  // the NaN point is skipped
  EXPECT_TRUE(out[0].isApprox(Point(1.5f, 10.3f, 1.5f), 1e-5f));
}

// The refinements at the edges of vertical features (ground_filter.hpp, step 3).
TEST(GroundFilter, AWallStripeWithNoRoadInItsCellIsVerticalThrough) {
  // A far wall's column: voxels 0.3 to 0.9 m up at (80.25, -7.75), road nowhere near.
  Points p;
  for (float z = 0.3f; z < 1.0f; z += 0.2f) p.emplace_back(80.25f, -7.75f, z);
  GroundFilter f;
  GroundResult r;
  f.run(p, r);
  ASSERT_EQ(r.voxels.size(), 4u);
  for (auto g : r.ground) EXPECT_EQ(g, 0);
  // The same stripe with road beside it: the road confirms its foot, the lowest voxel is road.
  for (float x = 79.05f; x < 81.5f; x += 0.2f)
    for (float y = -7.45f; y < -6.0f; y += 0.2f) p.emplace_back(x, y, 0.25f);
  f.run(p, r);
  for (std::size_t i = 0; i < r.voxels.size(); ++i)
    EXPECT_EQ(r.ground[i], r.voxels[i].z() < 0.4f ? 1 : 0) << r.voxels[i].transpose();
}

TEST(GroundFilter, AWallsTopLeaningIntoTheNextCellIsNotGround) {
  // A wall leaning 20 deg (a rolled car on a banked turn): its foot in one 0.5 m cell, its top
  // 0.4 m over, in the next cell, alone there (one voxel: no vote of its own).
  Points p;
  for (float x = 10.05f; x < 12; x += 0.2f) {
    for (float z = 0.05f; z < 1.2f; z += 0.2f) p.emplace_back(x, -7.9f + 0.36f * z, z);
    for (float y = -7.85f; y < -5; y += 0.2f) p.emplace_back(x, y, 0.0f);  // the road up to it
  }
  GroundFilter f;
  GroundResult r;
  f.run(p, r);
  int top_ground = 0, road_not_ground = 0;
  for (std::size_t i = 0; i < r.voxels.size(); ++i) {
    top_ground += r.voxels[i].z() > 0.8f && r.ground[i];
    road_not_ground += r.voxels[i].z() < 0.01f && r.voxels[i].y() > -7.0f && !r.ground[i];
  }
  EXPECT_EQ(top_ground, 0);
  EXPECT_EQ(road_not_ground, 0);
}

// A wall seen far ahead in stripes (one column each, 2 m apart) is grown through them; a pylon
// 1.5 m off the wall's line is not joined.
TEST(WallFit, FarStripesContinueTheWallAPylonBesideItDoesNot) {
  Points p;
  std::vector<std::vector<int>> clusters(1);
  auto wall_y = [](double x) { return -8 + 0.004 * x * x / 2; };  // curving left, R 250 m
  for (double x = -20; x < 25; x += 0.25)
    for (double z = 0.2; z < 1.2; z += 0.25) {
      clusters[0].push_back(static_cast<int>(p.size()));
      p.emplace_back(x, wall_y(x), z);
    }
  for (double x = 27; x < 80; x += 2) {  // stripes
    clusters.emplace_back();
    for (double z = 0.3; z < 1.2; z += 0.3) {
      clusters.back().push_back(static_cast<int>(p.size()));
      p.emplace_back(x, wall_y(x), z);
    }
  }
  clusters.emplace_back();  // a pylon 1.5 m inside the wall at x = 50
  for (double z = 0.1; z < 0.7; z += 0.2) {
    clusters.back().push_back(static_cast<int>(p.size()));
    p.emplace_back(50, wall_y(50) + 1.5, z);
  }
  const WallFit w = fit_wall(p, clusters, WallParams{});
  ASSERT_TRUE(w.valid);
  EXPECT_EQ(w.members.size(), clusters.size() - 1);
  EXPECT_EQ(std::count(w.members.begin(), w.members.end(), static_cast<int>(clusters.size() - 1)), 0);
  EXPECT_NEAR(w.distance, -8, 0.01);
  // The obstacle detector keeps the pylon and drops every stripe.
  const auto obstacles = find_obstacles(p, clusters, {{w, -1}}, ObstacleParams{});
  ASSERT_EQ(obstacles.size(), 1u);
  EXPECT_NEAR(obstacles[0].centroid.x(), 50, 1e-3);
  // Without growing (no gap allowed) the stripes beyond 25 m pass for obstacles.
  WallParams short_reach;
  short_reach.join_gap = 0;
  EXPECT_GT(find_obstacles(p, clusters, {{fit_wall(p, clusters, short_reach), -1}}, ObstacleParams{}).size(), 10u);
}

TEST(Obstacles, AFlatPatchAndARowsStreakAreNotObstacles) {
  Points p;
  std::vector<std::vector<int>> clusters(3);
  for (float x = 0; x < 1.2f; x += 0.2f)  // a patch of road tilted 20 deg, missed by the filter
    for (float y = 0; y < 0.5f; y += 0.2f) {
      clusters[0].push_back(static_cast<int>(p.size()));
      p.emplace_back(20 + x, 4 + y, 0.36f * y);
    }
  for (float x = 0; x < 0.8f; x += 0.2f) {  // one scan row across something: no height
    clusters[1].push_back(static_cast<int>(p.size()));
    p.emplace_back(60 + x, -2, 1.2f);
  }
  for (float z = 0.1f; z < 0.7f; z += 0.2f)  // a pylon seen by one column: a vertical line
    for (float y = 0; y < 0.3f; y += 0.15f) {
      clusters[2].push_back(static_cast<int>(p.size()));
      p.emplace_back(40, 1 + y, z);
    }
  const auto obstacles = find_obstacles(p, clusters, {}, ObstacleParams{});
  ASSERT_EQ(obstacles.size(), 1u);
  EXPECT_NEAR(obstacles[0].centroid.x(), 40, 1e-4);
}

// Far round a left turn: a pylon 120 m ahead and 20 m to the left, 5 m inside the curving right
// wall, seen as two one-row streaks 0.55 m apart. One obstacle, inside the corridor the wall
// draws; with no wall fitted the straight |y| <= 15 m corridor would drop it.
TEST(Obstacles, StackedStreaksAreOneObjectAndTheCorridorFollowsTheWall) {
  Points p;
  std::vector<std::vector<int>> clusters(1);
  auto wall_y = [](double x) { return -8 + x * x / (2 * 250.0); };
  for (double x = -20; x < 150; x += 0.5)
    for (double z = 0.2; z < 1.2; z += 0.3) {
      clusters[0].push_back(static_cast<int>(p.size()));
      p.emplace_back(x, wall_y(x), z);
    }
  const double py = wall_y(120) + 5;
  for (float z : {0.3f, 0.85f}) {
    clusters.emplace_back();
    for (float dy : {-0.15f, 0.0f, 0.15f}) {
      clusters.back().push_back(static_cast<int>(p.size()));
      p.emplace_back(120, py + dy, z);
    }
  }
  const WallFit w = fit_wall(p, clusters, WallParams{});
  ASSERT_TRUE(w.valid);
  const auto found = find_obstacles(p, clusters, {{w, -1}}, ObstacleParams{});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].centroid.y(), py, 1e-3);
  EXPECT_EQ(found[0].points, 6u);
  EXPECT_NEAR(found[0].size.z(), 0.55, 1e-5);
  // Without the wall: outside |y| <= 15 m.
  EXPECT_TRUE(find_obstacles(p, {clusters[1], clusters[2]}, {}, ObstacleParams{}).empty());
  // Without stacking, each streak alone has no height.
  ObstacleParams apart;
  apart.stack_gap = -1;
  EXPECT_TRUE(find_obstacles(p, clusters, {{w, -1}}, apart).empty());
}

TEST(FrameSet, ALateCloudIsDroppedNotAFrameOfItsOwn) {
  FrameSet<int> sets(2, 25'000'000);
  EXPECT_TRUE(sets.offer(0, 100'000'000, 1).empty());
  auto done = sets.offer(0, 150'000'000, 2);  // sensor 1 lost frame 100: closed partial
  ASSERT_EQ(done.size(), 1u);
  EXPECT_TRUE(sets.offer(1, 100'000'000, 3).empty());  // frame 100's cloud, late
  EXPECT_EQ(sets.late(), 1u);
  done = sets.offer(1, 150'000'000, 4);
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0], (std::vector<int>{2, 4}));
}

TEST(GroundFilter, PointsOutOfRangeAreSkipped) {
  Points p = {{1, 1, 0}, {1e10f, 0, 0}, {NAN, 0, 0}, {0, 0, -2e4f}};
  GroundFilter f;
  GroundResult r;
  f.run(p, r);
  ASSERT_EQ(r.voxels.size(), 1u);
  EXPECT_TRUE(r.voxels[0].isApprox(Point(1, 1, 0)));
}

// A cloud whose cells fit 31 bits is hashed with 32-bit keys (packed_keys.hpp), any other with
// cell_key's 64 bits: the answers are the same. One far point, alone in its voxel, its cell and
// its cluster, makes the banked scene too wide to pack.
TEST(GroundFilter, PackedAndFullKeysAgree) {
  const Scene s = banked_scene(9.2);
  Points wide = s.points;
  wide.emplace_back(9000, -9000, 0);
  GroundFilter f;
  GroundResult packed, full;
  f.run(s.points, packed);
  f.run(wide, full);
  ASSERT_EQ(full.voxels.size(), packed.voxels.size() + 1);
  for (std::size_t i = 0; i < packed.voxels.size(); ++i) {
    EXPECT_EQ(full.voxels[i], packed.voxels[i]) << i;
    EXPECT_EQ(full.ground[i], packed.ground[i]) << i;
  }
  EXPECT_EQ(full.voxels.back(), Point(9000, -9000, 0));
}

TEST(Clustering, PackedAndFullKeysAgree) {
  const Scene s = banked_scene(9.2);
  Points wide = s.points;
  wide.emplace_back(9000, -9000, 0);
  EuclideanClustering c({0.2f, 2, 100000});  // the road's 0.25 m grid apart; the wall and the pylon not
  std::vector<std::vector<int>> packed, full;
  c.run(s.points, packed);
  c.run(wide, full);
  EXPECT_GT(packed.size(), 1u);
  EXPECT_EQ(full, packed);  // the far point alone is below min_size
}

// The vectorised keys are cell_of's, negatives and cell borders included, for any point count.
TEST(PackedKeys, SameAsCellOfPointByPoint) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-150, 150);
  Points p;
  for (int i = 0; i < 1001; ++i) p.emplace_back(u(rng), u(rng) * 0.5f, u(rng) * 0.05f);
  p.emplace_back(-0.4f, 0.0f, -0.2f);  // on borders
  p.emplace_back(-1e-7f, 0.2f, 0.6f);
  const float inv = 1.0f / 0.2f;
  const Box box = box_of(p);
  ASSERT_TRUE(box.in_range);
  std::int32_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = cell_of(box.lo[a], inv), hi[a] = cell_of(box.hi[a], inv);
  const Packing pk(lo, hi, 3);
  ASSERT_TRUE(pk.ok);
  for (std::size_t n : {p.size(), p.size() - 1, p.size() - 2, std::size_t{3}}) {
    const Points q(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<std::uint32_t> keys(n);
    packed_keys(q, inv, pk, keys.data());
    for (std::size_t j = 0; j < n; ++j)
      EXPECT_EQ(keys[j], pk.key(cell_of(q[j].x(), inv), cell_of(q[j].y(), inv), cell_of(q[j].z(), inv))) << j;
  }
  Points bad = p;
  bad[7].y() = NAN;
  EXPECT_FALSE(box_of(bad).in_range);
  bad[7].y() = 2e4f;
  EXPECT_FALSE(box_of(bad).in_range);
  EXPECT_FALSE(box_of(Points{}).in_range);
}

// The obstacle detector's frames matched with the wall fits of their stamp (stamp_match.hpp).
TEST(StampMatch, AFrameGoesWithTheFitsOfItsStampOnceEachSideHasAnswered) {
  StampMatch<int, std::string> m({true, true});
  m.add_frame(100, 1);
  m.add_frame(200, 2);
  m.add_wall(1, 100, "left 100");  // the left detector stepped first
  EXPECT_FALSE(m.next()) << "the right fit of 100 is still to come";
  m.add_wall(0, 100, "right 100");
  auto a = m.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame, 1);
  ASSERT_EQ(a->walls.size(), 2u);
  EXPECT_EQ(a->walls[0], std::make_pair(std::string("right 100"), -1));
  EXPECT_EQ(a->walls[1], std::make_pair(std::string("left 100"), 1));
  EXPECT_FALSE(m.next());
  EXPECT_EQ(m.waiting(), 1u);
  // A later fit says this frame has none of that side; of two fits of one stamp the later counts.
  m.add_wall(1, 300, "left 300");
  m.add_wall(0, 200, "right 200");
  m.add_wall(0, 200, "right 200 again");
  a = m.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame, 2);
  ASSERT_EQ(a->walls.size(), 1u);
  EXPECT_EQ(a->walls[0], std::make_pair(std::string("right 200 again"), -1));
  EXPECT_EQ(m.unmatched(), 0u);
  EXPECT_EQ(m.waiting(), 0u);
}

TEST(StampMatch, ASilentDetectorHoldsNoMoreThanThreeFrames) {
  StampMatch<int, std::string> m({true, false});  // the left side not wired: never waited for
  for (int k = 1; k <= 3; ++k) m.add_frame(k, k);
  EXPECT_FALSE(m.next());
  m.add_frame(4, 4);
  auto a = m.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame, 1);
  EXPECT_TRUE(a->walls.empty());
  EXPECT_EQ(m.unmatched(), 1u);
  EXPECT_FALSE(m.next()) << "three wait again";
  m.add_wall(1, 2, "left 2");  // not wired: ignored
  m.add_wall(0, 2, "right 2");
  a = m.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame, 2);
  ASSERT_EQ(a->walls.size(), 1u);
  EXPECT_EQ(a->walls[0].second, -1);
  EXPECT_FALSE(m.next()) << "frame 3 waits for its own fit: the one of 2 is older";
}

TEST(StampMatch, OnlyTheLatestSixteenFitsAreKept) {
  StampMatch<int, std::string> m({true, false});
  for (int k = 1; k <= 17; ++k) m.add_wall(0, k, "right " + std::to_string(k));
  m.add_frame(1, 1);
  m.add_frame(2, 2);
  auto a = m.next();
  ASSERT_TRUE(a);
  EXPECT_TRUE(a->walls.empty()) << "the fit of 1 dropped, later ones kept: this frame has none";
  EXPECT_EQ(m.unmatched(), 0u);
  a = m.next();
  ASSERT_TRUE(a);
  ASSERT_EQ(a->walls.size(), 1u);
  EXPECT_EQ(a->walls[0].first, "right 2");
}

// With no wall detector wired a frame goes at once.
TEST(StampMatch, WithoutWallDetectorsEveryFrameGoesAtOnce) {
  StampMatch<int, std::string> m;
  m.add_frame(5, 5);
  auto a = m.next();
  ASSERT_TRUE(a);
  EXPECT_EQ(a->frame, 5);
  EXPECT_TRUE(a->walls.empty());
  EXPECT_FALSE(m.next());
}

// The car drives an arc (speed v, yaw rate w); a point fixed on the ground is measured dt after
// the frame's stamp, in the vehicle frame of then. Moved to the stamp it is where the vehicle
// frame of the stamp sees it: to a millimetre at 80 m/s turning on a 250 m radius, and on a
// straight; a sensor's window measured across 35 ms.
TEST(Deskew, APointMeasuredLaterIsWhereTheFrameOfTheStampSeesIt) {
  for (const PlanarMotion m : {PlanarMotion{80, 80.0 / 250}, PlanarMotion{80, -80.0 / 120}, PlanarMotion{80, 0}, PlanarMotion{0, 0}}) {
    const Eigen::Vector2d ground(45, -7);  // in the frame at the stamp (the car at the origin, heading +x)
    for (double dt : {-0.0175, -0.005, 0.0, 0.01, 0.0175, 0.05}) {
      // The car's pose at dt on the arc, exactly.
      const double a = m.yaw_rate * dt;
      const Eigen::Vector2d at = std::abs(m.yaw_rate) > 1e-12
                                     ? Eigen::Vector2d(std::sin(a), 1 - std::cos(a)) * (m.speed / m.yaw_rate)
                                     : Eigen::Vector2d(m.speed * dt, 0);
      const Eigen::Vector2d seen = Eigen::Rotation2Dd(-a) * (ground - at);  // the point in the frame at dt
      const Point moved = moved_to_stamp(Point(static_cast<float>(seen.x()), static_cast<float>(seen.y()), 1.5f),
                                         static_cast<float>(dt), m);
      EXPECT_NEAR(moved.x(), ground.x(), 1e-3) << m.speed << " " << m.yaw_rate << " dt " << dt;
      EXPECT_NEAR(moved.y(), ground.y(), 1e-3) << m.speed << " " << m.yaw_rate << " dt " << dt;
      EXPECT_EQ(moved.z(), 1.5f);
      if (dt != 0 && m.speed > 0) {
        EXPECT_GT((seen - ground).norm(), 0.3) << "the case tests nothing";
      }
    }
  }
}

// A cloud's points each at its own time: moved into the vehicle frame by the sensor's pose, then
// to the stamp; with no motion, the same as append_in_vehicle_frame; a point whose time is not
// finite is dropped, not placed.
TEST(Deskew, ACloudsPointsMovedEachByItsTime) {
  const SensorPose pose{1.5, 0, 0.5, 0, 0, M_PI / 2};
  const std::vector<float> x{10, 20, 30}, y{0, 1, 2}, z{0, 0, 0}, offset{-0.01f, 0.0f, std::nanf("")};
  Points still, plain;
  append_moved_to_stamp(pose, x.data(), y.data(), z.data(), nullptr, 0, 3, PlanarMotion{}, still);
  append_in_vehicle_frame(pose, x.data(), y.data(), z.data(), 3, plain);
  ASSERT_EQ(still.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(still[i].isApprox(plain[i])) << i;
  Points moving;
  const PlanarMotion m{50, 0};
  append_moved_to_stamp(pose, x.data(), y.data(), z.data(), offset.data(), 0.02, 3, m, moving);
  ASSERT_EQ(moving.size(), 2u);  // the third's time is NaN
  EXPECT_NEAR(moving[0].x(), plain[0].x() + 50 * (0.02 - 0.01), 1e-4);
  EXPECT_NEAR(moving[1].x(), plain[1].x() + 50 * 0.02, 1e-4);
  EXPECT_NEAR(moving[1].y(), plain[1].y(), 1e-5);
}
