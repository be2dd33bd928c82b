// PCL's generalized ICP and NDT as the baselines of our registration (mapping): a
// translation unit of their own, as PCL's registration headers are heavy.
#include "pcl_baseline.hpp"

#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/ndt.h>

#include <chrono>

namespace brickyard::baseline {

namespace {

pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(const Points& pts) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
  c->reserve(pts.size());
  for (const auto& p : pts) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return c;
}

// align() timed (the target's setup, PCL's kd-tree or NDT's voxels, inside setInputTarget, is not).
template <class Registration>
GicpResult timed_align(Registration& g, const Eigen::Matrix4d& guess) {
  pcl::PointCloud<pcl::PointXYZ> aligned;
  const auto t0 = std::chrono::steady_clock::now();
  g.align(aligned, guess.template cast<float>());
  GicpResult r;
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.transform = g.getFinalTransformation().template cast<double>();
  r.converged = g.hasConverged();
  return r;
}

}  // namespace

GicpResult ndt(const Points& source, const Points& target, const Eigen::Matrix4d& guess, float resolution) {
  pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> n;
  n.setResolution(resolution);
  n.setStepSize(0.1);
  n.setTransformationEpsilon(1e-3);
  n.setMaximumIterations(35);
  n.setInputSource(cloud(source));
  n.setInputTarget(cloud(target));
  return timed_align(n, guess);
}

GicpResult gicp(const Points& source, const Points& target, const Eigen::Matrix4d& guess, int max_iterations) {
  const auto src = cloud(source), tgt = cloud(target);
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> g;
  g.setInputSource(src);
  g.setInputTarget(tgt);
  g.setMaximumIterations(max_iterations);
  g.setTransformationEpsilon(1e-6);
  return timed_align(g, guess);
}

GicpResult gicp_tight(const Points& source, const Points& target, const Eigen::Matrix4d& guess) {
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> g;
  g.setInputSource(cloud(source));
  g.setInputTarget(cloud(target));
  g.setMaximumIterations(500);
  g.setTransformationEpsilon(1e-12);
  g.setRotationEpsilon(1e-12);
  g.setTranslationGradientTolerance(1e-8);
  g.setRotationGradientTolerance(1e-8);
  g.setMaximumOptimizerIterations(1000);
  return timed_align(g, guess);
}


}  // namespace brickyard::baseline
