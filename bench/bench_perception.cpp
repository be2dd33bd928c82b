// bench_perception: our perception pipeline beside PCL's on the same frames, in the same
// process. Frames: full 3-LiDAR frames of the simulated IMS (a straight and a 9.2 deg banked turn)
// and the real scans in data/lidar/. Per frame, the median of several runs of each stage:
//   ours: ground filter (voxel filter + hashed z-vote), clustering, walls + obstacles
//   PCL:  VoxelGrid, SACSegmentation plane (RANSAC) + ExtractIndices, EuclideanClusterExtraction
// and, on the same input as ours (our non-ground voxels), PCL's clustering alone. Prints the
// medians over the frames and the speed-ups, each the median of the per-frame ratios
// (docs/performance.md). One thread.
// Exits 1 when PCL's clustering of our non-ground voxels finds other clusters than ours (the two
// compare only when they partition the same points alike).
// usage: bench_perception [--quick] [--frames N] [--runs N]   (--quick: 2 frames, 3 runs)
#include "perception/common/pipeline.hpp"
#include "pcl_baseline.hpp"
#include "perception_scenes.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace brickyard;
using namespace brickyard::perception;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Median milliseconds of `runs` calls.
double time_ms(int runs, const std::function<void()>& f) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(t);
}

struct Row {
  std::string name;
  std::vector<double> points, ground, cluster, walls, ours, pcl_voxel, pcl_plane, pcl_cluster, pcl, pcl_cluster_same;
  int frames_clustered_apart = 0;
};

// The clusters' sizes, largest first: two partitions of the same points alike have the same.
std::vector<std::size_t> sizes(const std::vector<std::vector<int>>& clusters) {
  std::vector<std::size_t> n;
  for (const auto& c : clusters) n.push_back(c.size());
  std::sort(n.rbegin(), n.rend());
  return n;
}

void run_frame(const Points& frame, int runs, Row& row) {
  const PipelineParams pp;
  GroundFilter ground(pp.ground);
  EuclideanClustering clustering(pp.cluster);
  GroundResult g;
  Points features;
  std::vector<std::vector<int>> clusters;
  WallFit right;
  std::vector<Obstacle> obstacles;
  row.points.push_back(static_cast<double>(frame.size()));
  const double tg = time_ms(runs, [&] {
    ground.run(frame, g);
    features.clear();
    for (std::size_t i = 0; i < g.voxels.size(); ++i)
      if (!g.ground[i]) features.push_back(g.voxels[i]);
  });
  const double tc = time_ms(runs, [&] { clustering.run(features, clusters); });
  const double tw = time_ms(runs, [&] {
    right = fit_wall(features, clusters, pp.right);  // the right wall, as the graphs wire it
    obstacles = find_obstacles(features, clusters, {{right, -1}}, pp.obstacles);
  });
  Pipeline whole(pp);
  PipelineResult r;
  const double to = time_ms(runs, [&] { whole.run(frame, r); });
  // PCL: its pipeline with the same leaf, a 0.2 m plane threshold, the same tolerance and sizes.
  std::vector<baseline::PipelineTimes> pt;
  for (int k = 0; k < std::max(1, runs / 2); ++k)
    pt.push_back(baseline::pcl_pipeline(frame, pp.ground.leaf, 0.2f, pp.cluster.tolerance, pp.cluster.min_size, pp.cluster.max_size));
  std::vector<double> v, pl, cl, all;
  for (const auto& t : pt) {
    v.push_back(t.voxel_ms);
    pl.push_back(t.plane_ms);
    cl.push_back(t.cluster_ms);
    all.push_back(t.voxel_ms + t.plane_ms + t.cluster_ms);
  }
  std::vector<std::vector<int>> theirs;
  const double same = time_ms(std::max(1, runs / 2), [&] {
    theirs = baseline::euclidean_clusters(features, pp.cluster.tolerance, pp.cluster.min_size, pp.cluster.max_size);
  });
  if (sizes(theirs) != sizes(clusters)) {
    std::fprintf(stderr, "bench_perception: %s: PCL found %zu clusters, ours %zu\n", row.name.c_str(), theirs.size(), clusters.size());
    ++row.frames_clustered_apart;
  }
  row.ground.push_back(tg);
  row.cluster.push_back(tc);
  row.walls.push_back(tw);
  row.ours.push_back(to);
  row.pcl_voxel.push_back(median(v));
  row.pcl_plane.push_back(median(pl));
  row.pcl_cluster.push_back(median(cl));
  row.pcl.push_back(median(all));
  row.pcl_cluster_same.push_back(same);
}

// Speed-ups are the median of the per-frame ratios.
double median_ratio(const std::vector<double>& num, const std::vector<double>& den) {
  std::vector<double> q;
  for (std::size_t i = 0; i < num.size(); ++i) q.push_back(num[i] / den[i]);
  return median(q);
}

void append(Row& all, const Row& r) {
  for (auto [to, from] : {std::pair{&all.points, &r.points}, {&all.ground, &r.ground}, {&all.cluster, &r.cluster},
                          {&all.walls, &r.walls}, {&all.ours, &r.ours}, {&all.pcl_voxel, &r.pcl_voxel},
                          {&all.pcl_plane, &r.pcl_plane}, {&all.pcl_cluster, &r.pcl_cluster}, {&all.pcl, &r.pcl},
                          {&all.pcl_cluster_same, &r.pcl_cluster_same}})
    to->insert(to->end(), from->begin(), from->end());
  all.frames_clustered_apart += r.frames_clustered_apart;
}

void print(const Row& r) {
  const double ours = median(r.ours), pcl = median(r.pcl), c = median(r.cluster), cs = median(r.pcl_cluster_same);
  std::printf("| %s | %zu | %.0f | %.2f | %.2f | %.2f | **%.2f** | %.2f | %.2f | %.2f | **%.2f** | **%.1fx** | %.2f | **%.1fx** |\n",
              r.name.c_str(), r.points.size(), median(r.points), median(r.ground), c, median(r.walls), ours,
              median(r.pcl_voxel), median(r.pcl_plane), median(r.pcl_cluster), pcl, median_ratio(r.pcl, r.ours), cs,
              median_ratio(r.pcl_cluster_same, r.cluster));
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 10, runs = 7;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) frames = 2, runs = 3;
    else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_perception [--quick] [--frames N] [--runs N]\n");
      return 2;
    }
  }
  const std::string data = std::string(BRICKYARD_SOURCE_DIR) + "/data";
  std::printf("Medians over frames of the per-frame median of %d runs, ms, one thread. PCL pipeline: VoxelGrid, "
              "SACSegmentation plane (RANSAC, 0.2 m) + ExtractIndices, EuclideanClusterExtraction; the last two columns "
              "cluster our non-ground voxels with each.\n\n",
              runs);
  std::printf("| frames | n | points | ours: ground | clustering | walls + obstacles | **whole** | PCL: voxel | plane | clustering | **whole** | **speed-up** | PCL clustering, same input | **clustering speed-up** |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  scenes::ImsOptions o;
  scenes::Ims ims(data, o);
  Row all;
  all.name = "IMS, all simulated frames";
  for (int turn = 0; turn < 2; ++turn) {
    Row row;
    row.name = turn ? "IMS banked turn, 3 LiDARs" : "IMS straight, 3 LiDARs";
    const double s0 = turn ? ims.turn_s() : ims.straight_s();
    for (int k = 0; k < frames; ++k) run_frame(ims.frame(s0 + 10 * k, k % 3 - 1.0, 100 + k).points, runs, row);
    print(row);
    append(all, row);
  }
  print(all);
  for (const char* scan : {"patchwork_000000.pcd", "patchwork_000002.pcd", "cupcl_sample.pcd"}) {
    Row row;
    row.name = std::string("real scan ") + scan;
    run_frame(baseline::load_pcd(data + "/lidar/" + scan), runs, row);
    print(row);
    all.frames_clustered_apart += row.frames_clustered_apart;
  }
  return all.frames_clustered_apart == 0 ? 0 : 1;
}
