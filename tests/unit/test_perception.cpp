// Perception algorithms on synthetic clouds with known answers.
#include "common/clustering.hpp"
#include "common/ground_filter.hpp"

#include <gtest/gtest.h>

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
