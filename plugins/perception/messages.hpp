#pragma once
// Conversions between the perception algorithms' types and the wire messages, shared by the
// perception plugins.
#include <brickyard/msgs/ClusterList.h>
#include <brickyard/msgs/PointCloud.h>

#include "perception/common/deskew.hpp"
#include "perception/common/frame_set.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::perception {

inline SensorPose sensor_pose(const msgs::PointCloud& c) {
  return {c.sensor_x(), c.sensor_y(), c.sensor_z(), c.sensor_roll(), c.sensor_pitch(), c.sensor_yaw()};
}

// The cloud's points in the vehicle frame, appended to `out`; points that are not finite or lie
// beyond kMaxCoordinate once moved are dropped. Throws std::runtime_error when its coordinate
// sequences differ in length or its sensor pose is not finite (a malformed message names itself,
// it does not crash us).
// With `motion`, each point is also moved to the vehicle frame at frame_stamp_ns by the car's
// motion since (deskew.hpp): the cloud's stamp and each point's time_offset say when it was measured.
inline void append_vehicle_points(const msgs::PointCloud& c, Points& out, const PlanarMotion* motion = nullptr,
                                  std::int64_t frame_stamp_ns = 0) {
  const std::size_t n = c.x().size();
  if (c.y().size() != n || c.z().size() != n)
    throw std::runtime_error("PointCloud from '" + c.header().frame_id() + "': x, y, z have " + std::to_string(n) + ", " +
                             std::to_string(c.y().size()) + ", " + std::to_string(c.z().size()) + " values");
  if (!c.time_offset().empty() && c.time_offset().size() != n)
    throw std::runtime_error("PointCloud from '" + c.header().frame_id() + "': " + std::to_string(c.time_offset().size()) +
                             " time offsets for " + std::to_string(n) + " points");
  const SensorPose pose = sensor_pose(c);
  for (double v : {pose.x, pose.y, pose.z, pose.roll, pose.pitch, pose.yaw})
    if (!std::isfinite(v)) throw std::runtime_error("PointCloud from '" + c.header().frame_id() + "': sensor pose is not finite");
  if (!motion) return append_in_vehicle_frame(pose, c.x().data(), c.y().data(), c.z().data(), n, out);
  const double cloud_dt = 1e-9 * static_cast<double>(c.header().stamp_ns() - frame_stamp_ns);
  append_moved_to_stamp(pose, c.x().data(), c.y().data(), c.z().data(), c.time_offset().empty() ? nullptr : c.time_offset().data(),
                        cloud_dt, n, *motion, out);
}

// A vehicle-frame cloud of the chosen points (all when `keep` is null).
inline msgs::PointCloud vehicle_cloud(const Points& pts, const std::vector<std::uint8_t>* keep, std::uint8_t keep_value,
                                      std::int64_t stamp_ns, std::uint32_t seq) {
  msgs::PointCloud m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  std::vector<float> x, y, z;
  x.reserve(pts.size()); y.reserve(pts.size()); z.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (keep && (*keep)[i] != keep_value) continue;
    x.push_back(pts[i].x()); y.push_back(pts[i].y()); z.push_back(pts[i].z());
  }
  m.x(std::move(x)); m.y(std::move(y)); m.z(std::move(z));
  return m;
}

inline msgs::ClusterList cluster_list(const Points& pts, const std::vector<std::vector<int>>& clusters, std::int64_t stamp_ns,
                                      std::uint32_t seq) {
  msgs::ClusterList m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> sizes;
  for (const auto& c : clusters) {
    sizes.push_back(static_cast<std::uint32_t>(c.size()));
    for (int i : c) { x.push_back(pts[i].x()); y.push_back(pts[i].y()); z.push_back(pts[i].z()); }
  }
  m.x(std::move(x)); m.y(std::move(y)); m.z(std::move(z)); m.sizes(std::move(sizes));
  return m;
}

// The clusters of a message as points plus index lists. Throws on inconsistent lengths and on a
// point that is not finite or lies beyond kMaxCoordinate.
inline void read_clusters(const msgs::ClusterList& m, Points& pts, std::vector<std::vector<int>>& clusters) {
  const std::size_t n = m.x().size();
  std::size_t total = 0;
  for (auto s : m.sizes()) total += s;
  if (m.y().size() != n || m.z().size() != n || total != n)
    throw std::runtime_error("ClusterList: " + std::to_string(n) + " x values, " + std::to_string(m.y().size()) + " y, " +
                             std::to_string(m.z().size()) + " z, sizes summing to " + std::to_string(total));
  pts.clear();
  clusters.clear();
  for (std::size_t i = 0; i < n; ++i) {
    pts.emplace_back(m.x()[i], m.y()[i], m.z()[i]);
    if (!in_range(pts.back())) throw std::runtime_error("ClusterList: point " + std::to_string(i) + " is not finite or beyond 10 km");
  }
  int next = 0;
  for (auto s : m.sizes()) {
    std::vector<int> c(s);
    for (auto& i : c) i = next++;
    clusters.push_back(std::move(c));
  }
}

}  // namespace brickyard::perception
