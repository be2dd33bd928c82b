// Our perception beside PCL on the same points: the clustering partition must be PCL's, and on
// the real scans in data/lidar/ the ground filter is compared with PCL's RANSAC plane.
#include "perception/common/clustering.hpp"
#include "perception/common/ground_filter.hpp"
#include "pcl_baseline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace brickyard::perception;
namespace baseline = brickyard::baseline;

namespace {

using Partition = std::vector<std::vector<int>>;

// Clusters as a canonical set: each sorted, the list sorted.
Partition canonical(Partition p) {
  for (auto& c : p) std::sort(c.begin(), c.end());
  std::sort(p.begin(), p.end());
  return p;
}

void expect_same_partition(const Points& pts, ClusterParams cp) {
  EuclideanClustering ours(cp);
  Partition mine;
  ours.run(pts, mine);
  const Partition theirs = baseline::euclidean_clusters(pts, cp.tolerance, cp.min_size, cp.max_size);
  EXPECT_FALSE(theirs.empty());
  EXPECT_EQ(canonical(mine), canonical(theirs)) << pts.size() << " points, tolerance " << cp.tolerance;
}

// Clumps of random size and spread (some touching, some alone, some single points) in a 60 m box.
Points clumps(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> centre(-30, 30), spread(0.05f, 1.5f), unit(-1, 1);
  std::uniform_int_distribution<int> size(1, 200);
  Points p;
  for (int k = 0; k < count; ++k) {
    const Point c(centre(rng), centre(rng), 0.3f * centre(rng) / 30 + 1);
    const float s = spread(rng);
    for (int i = size(rng); i > 0; --i) p.emplace_back(c + s * Point(unit(rng), unit(rng), 0.5f * unit(rng)));
  }
  return p;
}

std::string lidar_file(const char* name) { return std::string(BRICKYARD_SOURCE_DIR) + "/data/lidar/" + name; }

}  // namespace

TEST(ClusteringVsPcl, SamePartitionOnRandomClumps) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Points p = clumps(seed, 150);
    expect_same_partition(p, {0.5f, 1, 100000});
    expect_same_partition(p, {0.3f, 5, 400});  // size limits drop the same components
  }
}

// The vertical features of a real scan: the input the clustering plugin sees.
TEST(ClusteringVsPcl, SamePartitionOnARealScansFeatures) {
  const Points scan = baseline::load_pcd(lidar_file("patchwork_000000.pcd"));
  GroundFilter f;
  GroundResult r;
  f.run(scan, r);
  const Points features = r.obstacles();
  ASSERT_GT(features.size(), 1000u);
  expect_same_partition(features, {0.5f, 3, 100000});
  expect_same_partition(features, {0.35f, 10, 5000});
}

TEST(VoxelFilterVsPcl, SameCentroids) {
  const Points p = clumps(4, 100);
  Points ours = voxel_filter(p, 0.2f), theirs = baseline::voxel_grid(p, 0.2f);
  ASSERT_EQ(ours.size(), theirs.size());
  auto less = [](const Point& a, const Point& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); };
  std::sort(ours.begin(), ours.end(), less);
  std::sort(theirs.begin(), theirs.end(), less);
  for (std::size_t i = 0; i < ours.size(); ++i) EXPECT_TRUE(ours[i].isApprox(theirs[i], 1e-4f)) << i;
}

// The real scans: the filter runs, and where the ground is a plane RANSAC (a plane within 15 deg
// of level, 0.2 m) agrees with us on most voxels. docs/results-perception.md reports the figures
// this prints.
TEST(GroundFilterVsPcl, RealScansAgreeWithRansacPlane) {
  for (const char* name : {"patchwork_000000.pcd", "patchwork_000002.pcd", "cupcl_sample.pcd"}) {
    const Points scan = baseline::load_pcd(lidar_file(name));
    ASSERT_GT(scan.size(), 50000u) << name;
    GroundFilter f;
    GroundResult r;
    f.run(scan, r);
    const auto plane = baseline::ransac_plane(r.voxels, 0.2f, 200);
    std::size_t agree = 0, ground = 0, inliers = 0, both = 0;
    for (std::size_t i = 0; i < r.voxels.size(); ++i) {
      agree += r.ground[i] == plane[i];
      ground += r.ground[i];
      inliers += plane[i];
      both += r.ground[i] && plane[i];
    }
    const double agreement = static_cast<double>(agree) / r.voxels.size();
    std::printf("%s: %zu points, %zu voxels, ground %.3f, RANSAC inliers %.3f, agreement %.3f, inliers we call ground %.3f\n",
                name, scan.size(), r.voxels.size(), static_cast<double>(ground) / r.voxels.size(),
                static_cast<double>(inliers) / r.voxels.size(), agreement, static_cast<double>(both) / inliers);
    // Floors under what this scan gives today (0.78 to 0.92 agreement, 0.79 to 0.94 of the
    // plane's inliers called ground): a regression of the filter shows here. The scans are
    // urban: kerbs, slopes and vegetation that one plane does not hold, so no more is asked.
    EXPECT_GE(agreement, 0.7) << name;
    EXPECT_GE(static_cast<double>(both) / inliers, 0.7) << name;
  }
}
