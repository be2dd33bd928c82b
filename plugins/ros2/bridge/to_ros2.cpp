#include "ros2/bridge/to_ros2.hpp"

namespace brickyard::ros2 {

namespace {

constexpr double kUnknownVariance = 1e6;

cdr::Ros2Pose planar_pose(double x, double y, double yaw) {
  cdr::Ros2Pose p;
  p.x = x;
  p.y = y;
  p.orientation = cdr::quaternion_from_rpy(0, 0, yaw);
  return p;
}

}  // namespace

std::string Frames::of(const std::string& ours) const {
  if (ours == "map") return map;
  if (ours.empty() || ours == "vehicle") return base;
  return ours;
}

cdr::Ros2Odometry odometry(const msgs::LocalizationEstimate& e, const Frames& f) {
  cdr::Ros2Odometry o;
  o.stamp_ns = e.header().stamp_ns();
  o.frame_id = f.map;
  o.child_frame_id = f.base;
  o.pose = planar_pose(e.x(), e.y(), e.yaw());
  // Ours is over (x, y, yaw): ROS 2's over (x, y, z, roll, pitch, yaw), row-major.
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) o.pose_covariance[cdr::kPlanarAxes[r] * 6 + cdr::kPlanarAxes[c]] = e.covariance()[r * 3 + c];
  for (int k : {2, 3, 4}) o.pose_covariance[k * 6 + k] = kUnknownVariance;
  o.linear = {e.speed(), 0, 0};
  o.angular = {0, 0, e.yaw_rate()};
  return o;
}

cdr::Ros2Transform map_to_base(const msgs::LocalizationEstimate& e, const Frames& f) {
  cdr::Ros2Transform t;
  t.stamp_ns = e.header().stamp_ns();
  t.frame_id = f.map;
  t.child_frame_id = f.base;
  t.x = e.x();
  t.y = e.y();
  t.rotation = cdr::quaternion_from_rpy(0, 0, e.yaw());
  return t;
}

std::string cloud_frame(const msgs::PointCloud& c, const Frames& f) {
  const std::string& own = c.header().frame_id();
  if (own.empty() || own == "vehicle" || own == "map") return "lidar_" + std::to_string(c.sensor_id());
  return f.of(own);
}

cdr::Ros2Transform base_to_sensor(const msgs::PointCloud& c, const Frames& f) {
  cdr::Ros2Transform t;
  t.stamp_ns = c.header().stamp_ns();
  t.frame_id = f.base;
  t.child_frame_id = cloud_frame(c, f);
  t.x = c.sensor_x();
  t.y = c.sensor_y();
  t.z = c.sensor_z();
  t.rotation = cdr::quaternion_from_rpy(c.sensor_roll(), c.sensor_pitch(), c.sensor_yaw());
  return t;
}

void cloud_columns(const msgs::PointCloud& c, const Frames& f, cdr::CloudColumns& out) {
  out.stamp_ns = c.header().stamp_ns();
  out.frame_id = cloud_frame(c, f);
  out.x = c.x();
  out.y = c.y();
  out.z = c.z();
  out.intensity = c.intensity();
  out.time_offset = c.time_offset();
}

std::vector<cdr::Ros2Marker> path_markers(const msgs::Path& p, const Frames& f) {
  cdr::Ros2Marker m;
  m.stamp_ns = p.header().stamp_ns();
  m.frame_id = f.of(p.header().frame_id());
  m.ns = "path";
  m.type = cdr::kMarkerLineStrip;
  m.scale = {0.3, 0, 0};  // a line strip's width is scale.x
  m.color = {0.1f, 0.9f, 0.2f, 1.0f};
  m.points.reserve(p.poses().size());
  for (const auto& q : p.poses()) m.points.push_back({q.x(), q.y(), 0.0});
  return {m};
}

std::vector<cdr::Ros2Marker> obstacle_markers(const msgs::ObstacleList& o, const Frames& f) {
  std::vector<cdr::Ros2Marker> out(1);
  out[0].stamp_ns = o.header().stamp_ns();
  out[0].frame_id = f.of(o.header().frame_id());
  out[0].ns = "obstacles";
  out[0].action = cdr::kMarkerDeleteAll;
  std::int32_t id = 0;
  for (const auto& b : o.obstacles()) {
    cdr::Ros2Marker m;
    m.stamp_ns = out[0].stamp_ns;
    m.frame_id = out[0].frame_id;
    m.ns = "obstacles";
    m.id = id++;
    m.pose.x = b.x();
    m.pose.y = b.y();
    m.pose.z = b.z();
    m.scale = {b.size_x(), b.size_y(), b.size_z()};
    m.color = {1.0f, 0.4f, 0.0f, 0.8f};
    out.push_back(std::move(m));
  }
  return out;
}

void navsatfix_values(const msgs::GnssFix& f, const drivers::LocalDatum& datum, const Frames& frames, cdr::NavSatFixValues& out) {
  out.stamp_ns = f.header().stamp_ns();
  // ROS 2's fix names the antenna's frame; ours names the map's, where its position is.
  const std::string& own = f.header().frame_id();
  out.frame_id = own.empty() || own == "map" || own == "vehicle" ? "gnss_" + std::to_string(f.receiver_id()) : frames.of(own);
  out.status = !f.valid() || f.fix_type() == 0 ? -1 : f.fix_type() == 3 ? 2 : 0;
  out.service = 1;  // GPS
  const drivers::Geodetic g = datum.to_geodetic({f.x(), f.y(), f.z()});
  out.latitude = g.latitude_deg;
  out.longitude = g.longitude_deg;
  out.altitude = g.height_m;
  out.position_covariance = {f.sigma_x() * f.sigma_x(), 0, 0, 0, f.sigma_y() * f.sigma_y(), 0, 0, 0, f.sigma_z() * f.sigma_z()};
  out.covariance_type = 2;  // diagonal known
}

void imu_values(const msgs::Imu& m, const Frames& f, cdr::ImuValues& out) {
  out.stamp_ns = m.header().stamp_ns();
  out.frame_id = f.of(m.header().frame_id());
  out.orientation = {0, 0, 0, 1};
  out.has_orientation = false;
  out.angular_velocity = {m.gyro_x(), m.gyro_y(), m.gyro_z()};
  out.linear_acceleration = {m.accel_x(), m.accel_y(), m.accel_z()};
}

}  // namespace brickyard::ros2
