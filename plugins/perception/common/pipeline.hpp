#pragma once
// The chain the four perception plugins form in a graph (ground filter -> clustering -> wall
// detectors -> obstacle detector), in one call: what the evaluation and the benchmark run.
#include "clustering.hpp"
#include "ground_filter.hpp"
#include "obstacles.hpp"
#include "wall_fit.hpp"

namespace brickyard::perception {

struct PipelineParams {
  GroundParams ground;
  ClusterParams cluster;
  WallParams right;                          // side -1
  WallParams left = [] { WallParams w; w.side = 1; return w; }();
  bool fit_left = false;  // the graphs wire the right wall's detector only, as the paper follows it
  ObstacleParams obstacles;
};

struct PipelineResult {
  GroundResult ground;
  Points features;  // non-ground voxels
  std::vector<std::vector<int>> clusters;
  WallFit right, left;
  std::vector<Obstacle> obstacles;
};

class Pipeline {
 public:
  explicit Pipeline(PipelineParams p = {}) : p_(p), ground_(p.ground), clustering_(p.cluster) {}
  const PipelineParams& params() const { return p_; }
  void run(const Points& frame, PipelineResult& r) {
    ground_.run(frame, r.ground);
    r.features.clear();
    for (std::size_t i = 0; i < r.ground.voxels.size(); ++i)
      if (!r.ground.ground[i]) r.features.push_back(r.ground.voxels[i]);
    clustering_.run(r.features, r.clusters);
    r.right = fit_wall(r.features, r.clusters, p_.right);
    r.left = p_.fit_left ? fit_wall(r.features, r.clusters, p_.left) : WallFit{};
    std::vector<std::pair<WallFit, int>> walls{{r.right, -1}};
    if (p_.fit_left) walls.emplace_back(r.left, 1);
    r.obstacles = find_obstacles(r.features, r.clusters, walls, p_.obstacles);
  }

 private:
  PipelineParams p_;
  GroundFilter ground_;
  EuclideanClustering clustering_;
};

}  // namespace brickyard::perception
