// PCL's generalized ICP as the baseline of our registration (mapping, issue 17): a translation
// unit of its own, as PCL's registration headers are heavy.
#include "pcl_baseline.hpp"

#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>

#include <chrono>

namespace brickyard::baseline {

GicpResult gicp(const Points& source, const Points& target, const Eigen::Matrix4d& guess, int max_iterations) {
  auto cloud = [](const Points& pts) {
    pcl::PointCloud<pcl::PointXYZ>::Ptr c(new pcl::PointCloud<pcl::PointXYZ>);
    c->reserve(pts.size());
    for (const auto& p : pts) c->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    return c;
  };
  const auto src = cloud(source), tgt = cloud(target);
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> g;
  g.setInputSource(src);
  g.setInputTarget(tgt);
  g.setMaximumIterations(max_iterations);
  g.setTransformationEpsilon(1e-6);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  const auto t0 = std::chrono::steady_clock::now();
  g.align(aligned, guess.cast<float>());
  GicpResult r;
  r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.transform = g.getFinalTransformation().cast<double>();
  r.converged = g.hasConverged();
  return r;
}

}  // namespace brickyard::baseline
