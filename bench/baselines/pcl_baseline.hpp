#pragma once
// PCL as the baseline of our perception (tests and benchmarks only; no plugin links PCL). The
// interface speaks our types so that PCL headers stay inside pcl_baseline.cpp, the one
// translation unit that pays for them.
#include "perception/common/points.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace brickyard::baseline {

using perception::Points;

// Loads x, y, z of a PCD file (any PCL-readable encoding); non-finite points dropped. Throws
// std::runtime_error naming the file when it cannot be read.
Points load_pcd(const std::string& path);

// pcl::EuclideanClusterExtraction with a KdTree, as PCL documents it: the clusters' index lists,
// each sorted, the clusters ordered as PCL returns them (largest first).
std::vector<std::vector<int>> euclidean_clusters(const Points& points, float tolerance, int min_size, int max_size);

// pcl::VoxelGrid centroids.
Points voxel_grid(const Points& points, float leaf);

// pcl::SACSegmentation with RANSAC, a plane within 15 deg of level (SACMODEL_PERPENDICULAR_PLANE
// about z): 1 for the plane's inliers.
std::vector<std::uint8_t> ransac_plane(const Points& points, float distance_threshold, int max_iterations = 100);

// The PCL pipeline the issue names, on one frame: VoxelGrid, RANSAC plane removal, Euclidean
// clustering of the rest. Times in milliseconds per stage.
struct PipelineTimes {
  double voxel_ms = 0, plane_ms = 0, cluster_ms = 0;
  std::size_t voxels = 0, non_ground = 0, clusters = 0;
};
PipelineTimes pcl_pipeline(const Points& frame, float leaf, float plane_threshold, float tolerance, int min_size, int max_size);

// pcl::GeneralizedIterativeClosestPoint (in pcl_gicp.cpp): the transform that brings `source`
// onto `target`, from `guess`, with PCL's defaults (20 neighbours per covariance) but
// `max_iterations` and a transformation epsilon of 1e-6; the wall time of align().
struct GicpResult {
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  bool converged = false;
  double ms = 0;
};
GicpResult gicp(const Points& source, const Points& target, const Eigen::Matrix4d& guess, int max_iterations = 64);
// The same with every stopping rule of PCL's tightened: 500 rounds, transformation and rotation
// epsilons 1e-12, BFGS gradient tolerances 1e-8 and 1,000 optimizer iterations a round (does
// PCL's answer move when it is let run?).
GicpResult gicp_tight(const Points& source, const Points& target, const Eigen::Matrix4d& guess);
// pcl::NormalDistributionsTransform (pcl_gicp.cpp): voxels of `resolution` m, step 0.1, epsilon
// 1e-3, at most 35 iterations (PCL's tutorial's settings); the wall time of align().
GicpResult ndt(const Points& source, const Points& target, const Eigen::Matrix4d& guess, float resolution = 1.0f);

}  // namespace brickyard::baseline
