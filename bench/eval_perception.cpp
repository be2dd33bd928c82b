// The perception evaluation of simulated full 3-LiDAR frames of IMS scored against the
// simulator's ground truth, on a straight and in a banked turn (9.2 deg, and 20 deg as at Las
// Vegas). Prints the tables of docs/results-perception.md and checks the targets: ground
// precision and recall >= 0.98, wall distance error p95 <= 0.10 m, no false obstacles; exit 1 if
// one is missed. The pylon detection range is reported (goal >= 80 m).
// usage: eval_perception [--seed N]
#include "perception/common/pipeline.hpp"
#include "pcl_baseline.hpp"
#include "perception_scenes.hpp"
#include "sim/common/perception_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using namespace brickyard;
using namespace brickyard::perception;
using sim::Surface;

namespace {

double percentile(const std::vector<double>& v, double q) { return sim::PerceptionScore::percentile(v, q); }

// Each voxel's truth: the surface most of its points hit. The voxel filter keeps no point
// indices, so they are found again by the voxel key.
std::vector<Surface> voxel_truth(const scenes::Frame& f, const PipelineResult& r, float leaf) {
  std::map<std::uint64_t, std::array<int, 4>> votes;
  const float inv = 1.0f / leaf;
  auto key = [&](const Point& p) { return cell_key(cell_of(p.x(), inv), cell_of(p.y(), inv), cell_of(p.z(), inv)); };
  // Grass beyond the edges is ground as the road is.
  for (std::size_t i = 0; i < f.points.size(); ++i)
    ++votes[key(f.points[i])][static_cast<int>(f.surface[i] == Surface::grass ? Surface::road : f.surface[i])];
  // Centroids lie in their voxel, so the centroid's key is the voxel's.
  std::vector<Surface> t;
  for (const Point& v : r.ground.voxels) {
    const auto& a = votes[key(v)];
    t.push_back(static_cast<Surface>(std::max_element(a.begin(), a.end()) - a.begin()));
  }
  return t;
}

struct Score {
  std::size_t tp = 0, fp = 0, fn = 0, fp_feet = 0, frames = 0, false_obstacles = 0, wall_frames = 0;
  std::size_t pcl_tp = 0, pcl_fp = 0, pcl_fn = 0;  // PCL's RANSAC plane (within 15 deg of level, 0.2 m) as the ground
  std::vector<double> wall_err, points, voxels;
};

void score_frame(const scenes::Ims& ims, const scenes::Frame& f, const PipelineResult& r, float leaf, Score& s) {
  const auto truth = voxel_truth(f, r, leaf);
  const auto plane = baseline::ransac_plane(r.ground.voxels, 0.2f, 100);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const bool is_road = truth[i] == Surface::road;
    s.pcl_tp += plane[i] && is_road;
    s.pcl_fp += plane[i] && !is_road;
    s.pcl_fn += !plane[i] && is_road;
  }
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const bool road = truth[i] == Surface::road;
    s.tp += r.ground.ground[i] && road;
    s.fn += !r.ground.ground[i] && road;
    if (r.ground.ground[i] && !road) {
      ++s.fp;
      // A foot: a wall or pylon voxel whose centroid lies within one leaf of the road surface.
      const Eigen::Vector3d w = f.world_from_body * r.ground.voxels[i].cast<double>();
      const sim::Frenet at = ims.track().project(w.x(), w.y());
      s.fp_feet += w.z() - ims.track().road_z(at) < leaf;
    }
  }
  ++s.frames;
  s.points.push_back(static_cast<double>(f.points.size()));
  s.voxels.push_back(static_cast<double>(r.ground.voxels.size()));
  if (r.right.valid) {
    s.wall_err.push_back(std::abs(r.right.distance - ims.wall_y(f.world_from_body, -1)));
    ++s.wall_frames;
  }
  for (const Obstacle& o : r.obstacles) {
    bool pylon = false;
    for (std::size_t k = 0; k < ims.track().spec().pylons.size(); ++k) {
      const Eigen::Vector3d p = ims.pylon_in_body(f.world_from_body, k);
      pylon = pylon || std::hypot(o.centroid.x() - p.x(), o.centroid.y() - p.y()) < 1.0;
    }
    s.false_obstacles += !pylon;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
    else {
      std::fprintf(stderr, "usage: eval_perception [--seed N]\n");
      return 2;
    }
  }
  const std::string data = std::string(BRICKYARD_SOURCE_DIR) + "/data";
  PipelineResult r;
  const float leaf = GroundParams{}.leaf;
  bool ok = true;

  // 1. Ground, walls, false obstacles: 30 frames per scene, the car every 10 m over 100 m of the
  // straight or the turn at d = -4, 0, +4 m, one pylon in each scene's view. The world is the
  // simulator's default (outer wall only); the rows with the inner wall too (2 m beyond the
  // inside edge) are reported, not targets.
  std::printf("## Ground, wall and false obstacles (seed %llu)\n\n", static_cast<unsigned long long>(seed));
  std::printf("| scene | frames | points/frame | voxels/frame | ground precision | precision, feet unscored | ground recall | wall fits | wall error p50 | wall error p95 | false obstacles | PCL plane: precision | PCL plane: recall |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  struct SceneSpec {
    const char* name;
    bool turn;
    double bank;
    bool inner_wall, target;
  };
  const SceneSpec specs[] = {{"straight", false, 9.2, false, true},
                             {"banked turn 9.2 deg", true, 9.2, false, true},
                             {"banked turn 20 deg", true, 20.0, false, true},
                             {"straight, inner wall too", false, 9.2, true, false},
                             {"banked turn 9.2 deg, inner wall too", true, 9.2, true, false}};
  for (const SceneSpec& spec : specs) {
    scenes::ImsOptions o;
    o.bank_deg = spec.bank;
    o.inner_wall = spec.inner_wall;
    scenes::Ims probe(data, o);
    const double s0 = spec.turn ? probe.turn_s() : probe.straight_s();
    o.pylons = {sim::Pylon{s0 + 150, 1.5, 0.2, 0.7}};
    scenes::Ims ims(data, o);
    PipelineParams pp;
    pp.fit_left = spec.inner_wall;  // a left wall detector where there is a left wall
    Pipeline pipe(pp);
    Score sc;
    for (int k = 0; k < 10; ++k)
      for (double d : {-4.0, 0.0, 4.0}) {
        const scenes::Frame f = ims.frame(s0 + 10 * k, d, seed * 1000 + k * 10 + static_cast<int>(d + 4));
        pipe.run(f.points, r);
        score_frame(ims, f, r, leaf, sc);
      }
    const double precision = static_cast<double>(sc.tp) / (sc.tp + sc.fp), recall = static_cast<double>(sc.tp) / (sc.tp + sc.fn);
    const double precision_feet = static_cast<double>(sc.tp) / (sc.tp + sc.fp - sc.fp_feet);
    const double p50 = percentile(sc.wall_err, 0.5), p95 = percentile(sc.wall_err, 0.95);
    std::printf("| %s%s | %zu | %.0f | %.0f | %.4f | %.4f | %.4f | %zu/%zu | %.3f m | %.3f m | %zu | %.4f | %.4f |\n", spec.name,
                spec.target ? "" : " (not a target)", sc.frames, percentile(sc.points, 0.5), percentile(sc.voxels, 0.5), precision,
                precision_feet, recall, sc.wall_frames, sc.frames, p50, p95, sc.false_obstacles,
                static_cast<double>(sc.pcl_tp) / (sc.pcl_tp + sc.pcl_fp), static_cast<double>(sc.pcl_tp) / (sc.pcl_tp + sc.pcl_fn));
    const bool met = precision_feet >= 0.98 && recall >= 0.98 && p95 <= 0.10 && sc.false_obstacles == 0 && sc.wall_frames == sc.frames;
    if (!met && spec.target) {
      std::printf("  ^ target missed (precision, feet unscored, and recall >= 0.98; wall p95 <= 0.10 m, a fit in every frame; no false obstacles)\n");
      ok = false;
    }
  }

  // 2. Pylon detection range: a 0.7 m pylon 1.5 m left of the centre line, the car approaching
  // from 200 m in 5 m steps at three lateral offsets, five noise seeds each; on the straight
  // (the goal) and in the banked turn (reported). Detected: an obstacle within 1 m of the pylon.
  // Reliable range: the largest distance from which it is detected in every frame nearer (down
  // to 10 m) and in every seed.
  std::printf("\n## Pylon detection range (0.7 m high, r 0.2 m, d = 1.5 m)\n\n");
  std::printf("| where | car d | reliable from | first seen at |\n|---|---|---|---|\n");
  double worst_reliable = 1e9;
  for (int turn = 0; turn < 2; ++turn) {
    scenes::ImsOptions o;
    scenes::Ims probe(data, o);
    const double pylon_s = (turn ? probe.turn_s() : probe.straight_s()) + 250;
    o.pylons = {sim::Pylon{pylon_s, 1.5, 0.2, 0.7}};
    scenes::Ims ims(data, o);
    Pipeline pipe;
    for (double d : {-4.0, 0.0, 4.0}) {
      double reliable = 0, first = 0;
      bool broken = false;
      for (double dist = 10; dist <= 200; dist += 5) {
        int seen = 0;
        const int seeds = 5;
        for (int k = 0; k < seeds; ++k) {
          const scenes::Frame f = ims.frame(pylon_s - dist - 2.342, d, seed * 7919 + k * 131 + static_cast<int>(dist));
          pipe.run(f.points, r);
          const Eigen::Vector3d p = ims.pylon_in_body(f.world_from_body, 0);
          bool hit = false;
          for (const Obstacle& ob : r.obstacles) hit = hit || std::hypot(ob.centroid.x() - p.x(), ob.centroid.y() - p.y()) < 1.0;
          seen += hit;
        }
        if (seen > 0) first = dist;
        if (seen == seeds && !broken) reliable = dist;
        if (seen < seeds) broken = true;
      }
      if (!turn) worst_reliable = std::min(worst_reliable, reliable);
      std::printf("| %s | %+.0f m | %.0f m | %.0f m |\n", turn ? "banked turn 9.2 deg" : "straight", d, reliable, first);
    }
  }
  std::printf("\nreliable pylon detection range on the straight (worst offset): %.0f m (goal >= 80 m: %s)\n", worst_reliable,
              worst_reliable >= 80 ? "met" : "not met");
  std::printf("\n%s\n", ok ? "all targets met" : "TARGETS MISSED");
  return ok ? 0 : 1;
}
