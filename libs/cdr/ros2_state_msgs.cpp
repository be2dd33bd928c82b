#include "cdr/ros2_state_msgs.hpp"

#include "cdr/cdr_writer.hpp"

#include <cmath>

namespace brickyard::cdr {

namespace {

void put_point(CdrWriter& w, double x, double y, double z) {
  w.put<double>(x);
  w.put<double>(y);
  w.put<double>(z);
}
void put_quaternion(CdrWriter& w, const Quaternion& q) {
  put_point(w, q.x, q.y, q.z);
  w.put<double>(q.w);
}
void put_pose(CdrWriter& w, const Ros2Pose& p) {
  put_point(w, p.x, p.y, p.z);
  put_quaternion(w, p.orientation);
}
void put_covariance(CdrWriter& w, const std::array<double, 36>& c) {
  for (double v : c) w.put<double>(v);
}

// One Marker, Humble's every member: what a marker here does not use left empty.
void put_marker(CdrWriter& w, const Ros2Marker& m) {
  w.put_header(m.stamp_ns, m.frame_id);
  w.put_string(m.ns);
  w.put<std::int32_t>(m.id);
  w.put<std::int32_t>(m.type);
  w.put<std::int32_t>(m.action);
  put_pose(w, m.pose);
  put_point(w, m.scale[0], m.scale[1], m.scale[2]);
  for (float c : m.color) w.put<float>(c);
  w.put_time(m.lifetime_ns);
  w.put<std::uint8_t>(0);  // frame_locked
  w.put<std::uint32_t>(static_cast<std::uint32_t>(m.points.size()));
  for (const auto& p : m.points) put_point(w, p[0], p[1], p[2]);
  w.put<std::uint32_t>(0);  // colors: the marker's one color
  w.put_string("");         // texture_resource
  w.put_header(0, "");      // texture: a CompressedImage with no data
  w.put_string("");
  w.put<std::uint32_t>(0);
  w.put<std::uint32_t>(0);  // uv_coordinates
  w.put_string("");         // text
  w.put_string("");         // mesh_resource
  w.put_string("");         // mesh_file: no file, no data
  w.put<std::uint32_t>(0);
  w.put<std::uint8_t>(0);   // mesh_use_embedded_materials
}

}  // namespace

Quaternion quaternion_from_rpy(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy};
}

void write_odometry(const Ros2Odometry& o, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put_header(o.stamp_ns, o.frame_id);
  w.put_string(o.child_frame_id);
  put_pose(w, o.pose);
  put_covariance(w, o.pose_covariance);
  put_point(w, o.linear[0], o.linear[1], o.linear[2]);
  put_point(w, o.angular[0], o.angular[1], o.angular[2]);
  put_covariance(w, o.twist_covariance);
}

Ros2Odometry read_odometry(const unsigned char* cdr, std::size_t size) {
  CdrReader r(cdr, size, "Odometry");
  Ros2Odometry o;
  o.stamp_ns = r.time_ns("header.stamp");
  o.frame_id = r.string("header.frame_id");
  o.child_frame_id = r.string("child_frame_id");
  double* pose[7] = {&o.pose.x, &o.pose.y, &o.pose.z, &o.pose.orientation.x, &o.pose.orientation.y, &o.pose.orientation.z, &o.pose.orientation.w};
  for (double* v : pose) *v = r.get<double>("pose.pose");
  for (double& c : o.pose_covariance) c = r.get<double>("pose.covariance");
  for (double& v : o.linear) v = r.get<double>("twist.twist.linear");
  for (double& v : o.angular) v = r.get<double>("twist.twist.angular");
  for (double& c : o.twist_covariance) c = r.get<double>("twist.covariance");
  return o;
}

double yaw_of(const Quaternion& q) { return std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z)); }

void write_pose_stamped(std::int64_t stamp_ns, const std::string& frame_id, const Ros2Pose& pose, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put_header(stamp_ns, frame_id);
  put_pose(w, pose);
}

void write_tf_message(const std::vector<Ros2Transform>& transforms, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(transforms.size()));
  for (const Ros2Transform& t : transforms) {
    w.put_header(t.stamp_ns, t.frame_id);
    w.put_string(t.child_frame_id);
    put_point(w, t.x, t.y, t.z);
    put_quaternion(w, t.rotation);
  }
}

void write_marker_array(const std::vector<Ros2Marker>& markers, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(markers.size()));
  for (const Ros2Marker& m : markers) put_marker(w, m);
}

}  // namespace brickyard::cdr
