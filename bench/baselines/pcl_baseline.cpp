#include "pcl_baseline.hpp"

#include <pcl/ModelCoefficients.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace brickyard::baseline {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr to_pcl(const Points& pts) {
  Cloud::Ptr c(new Cloud);
  c->reserve(pts.size());
  for (const auto& p : pts) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return c;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<std::vector<int>> extract(const Cloud::Ptr& c, float tolerance, int min_size, int max_size) {
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(c);
  std::vector<pcl::PointIndices> found;
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(tolerance);
  ec.setMinClusterSize(min_size);
  ec.setMaxClusterSize(max_size);
  ec.setSearchMethod(tree);
  ec.setInputCloud(c);
  ec.extract(found);
  std::vector<std::vector<int>> out;
  for (const auto& f : found) out.emplace_back(f.indices.begin(), f.indices.end());
  return out;
}

pcl::PointIndices::Ptr plane_inliers(const Cloud::Ptr& c, float threshold, int max_iterations) {
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  seg.setOptimizeCoefficients(true);
  // A plane within 15 deg of level: the usual ground removal (a free plane may lock onto a wall).
  seg.setModelType(pcl::SACMODEL_PERPENDICULAR_PLANE);
  seg.setAxis(Eigen::Vector3f::UnitZ());
  seg.setEpsAngle(15.0 * M_PI / 180.0);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(threshold);
  seg.setMaxIterations(max_iterations);
  seg.setInputCloud(c);
  pcl::PointIndices::Ptr inliers(new pcl::PointIndices);
  pcl::ModelCoefficients coefficients;
  seg.segment(*inliers, coefficients);
  return inliers;
}

}  // namespace

Points load_pcd(const std::string& path) {
  Cloud c;
  if (pcl::io::loadPCDFile<pcl::PointXYZ>(path, c) < 0) throw std::runtime_error(path + ": not a readable PCD file");
  Points out;
  out.reserve(c.size());
  for (const auto& p : c)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) out.emplace_back(p.x, p.y, p.z);
  return out;
}

std::vector<std::vector<int>> euclidean_clusters(const Points& points, float tolerance, int min_size, int max_size) {
  return extract(to_pcl(points), tolerance, min_size, max_size);
}

Points voxel_grid(const Points& points, float leaf) {
  pcl::VoxelGrid<pcl::PointXYZ> vg;
  vg.setInputCloud(to_pcl(points));
  vg.setLeafSize(leaf, leaf, leaf);
  Cloud out;
  vg.filter(out);
  Points r;
  for (const auto& p : out) r.emplace_back(p.x, p.y, p.z);
  return r;
}

std::vector<std::uint8_t> ransac_plane(const Points& points, float distance_threshold, int max_iterations) {
  std::vector<std::uint8_t> mask(points.size(), 0);
  const auto inliers = plane_inliers(to_pcl(points), distance_threshold, max_iterations);  // held: the loop reads into it
  for (int i : inliers->indices) mask[i] = 1;
  return mask;
}

PipelineTimes pcl_pipeline(const Points& frame, float leaf, float plane_threshold, float tolerance, int min_size, int max_size) {
  PipelineTimes t;
  const Cloud::Ptr in = to_pcl(frame);  // conversion not timed: PCL users hold PCL clouds
  auto t0 = std::chrono::steady_clock::now();
  Cloud::Ptr voxels(new Cloud);
  pcl::VoxelGrid<pcl::PointXYZ> vg;
  vg.setInputCloud(in);
  vg.setLeafSize(leaf, leaf, leaf);
  vg.filter(*voxels);
  t.voxel_ms = ms_since(t0);
  t.voxels = voxels->size();
  t0 = std::chrono::steady_clock::now();
  const auto inliers = plane_inliers(voxels, plane_threshold, 100);
  Cloud::Ptr rest(new Cloud);
  pcl::ExtractIndices<pcl::PointXYZ> ex;
  ex.setInputCloud(voxels);
  ex.setIndices(inliers);
  ex.setNegative(true);
  ex.filter(*rest);
  t.plane_ms = ms_since(t0);
  t.non_ground = rest->size();
  t0 = std::chrono::steady_clock::now();
  t.clusters = extract(rest, tolerance, min_size, max_size).size();
  t.cluster_ms = ms_since(t0);
  return t;
}

}  // namespace brickyard::baseline
