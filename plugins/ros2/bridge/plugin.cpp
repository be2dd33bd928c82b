// ros2.bridge: the car as ROS 2's tools see it (docs/ros2.md, "A bridge to ROS 2's tools"): the
// estimate as nav_msgs/Odometry, geometry_msgs/PoseStamped and /tf's map-to-base transform, a
// cloud as sensor_msgs/PointCloud2 (its sensor's transform on tf), the path and the obstacles as
// visualization_msgs/MarkerArray, the IMU as sensor_msgs/Imu, fixes as sensor_msgs/NavSatFix about
// a datum. Each input optional; each output ROS 2's standard type, written as its CDR
// (ros2/bridge/to_ros2.hpp): with transport.naming "ros2", `/brickyard/NODE/PORT` to ROS 2 and RViz.
#include <brickyard/plugin.hpp>

#include "ros2/bridge/to_ros2.hpp"

#include <array>
#include <optional>

namespace {

using namespace brickyard;

struct Settings {
  ros2::Frames frames;
  std::optional<double> datum_latitude, datum_longitude;
  double datum_altitude = 0;
};

// Each output's type is ROS 2's: a parameter of one choice, read by the host (the type it
// registers the wire as), never by the plugin.
void declare_type(ParamBinding<Settings>& b, const char* name, const char* type) {
  b.declare(ParamSpec::string(name, type).one_of({type}).doc(std::string("the output's type: ROS 2's ") + type));
}

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("map_frame", &Settings::frames, &ros2::Frames::map).doc("what our \"map\" frame is called (REP 105: map)");
  b.bind("base_frame", &Settings::frames, &ros2::Frames::base).doc("what our \"vehicle\" frame is called (REP 105: base_link)");
  declare_type(b, "odom_type", "nav_msgs::msg::Odometry");
  declare_type(b, "pose_type", "geometry_msgs::msg::PoseStamped");
  declare_type(b, "tf_type", "tf2_msgs::msg::TFMessage");
  declare_type(b, "points_type", "sensor_msgs::msg::PointCloud2");
  declare_type(b, "markers_type", "visualization_msgs::msg::MarkerArray");
  declare_type(b, "imu_type", "sensor_msgs::msg::Imu");
  declare_type(b, "fix_type", "sensor_msgs::msg::NavSatFix");
  b.bind("datum_latitude", &Settings::datum_latitude).in_unit("deg").range(-90, 90).doc("the map frame's origin (a gnss input wired: required)");
  b.bind("datum_longitude", &Settings::datum_longitude).in_unit("deg").range(-180, 180).doc("the map frame's origin");
  b.bind("datum_altitude", &Settings::datum_altitude).in_unit("m").range(-1000, 10000).doc("above the WGS84 ellipsoid");
  return b;
}

struct Ports {
  Input<msgs::LocalizationEstimate> estimate;
  std::array<Input<msgs::PointCloud>, 4> cloud;
  Input<msgs::Path> path;
  Input<msgs::ObstacleList> obstacles;
  Input<msgs::Imu> imu;
  std::array<Input<msgs::GnssFix>, 2> gnss;
  AnyOutput odom, pose, tf, points, path_markers, obstacle_markers, imu_data, fix;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("estimate", &Ports::estimate).doc("the fusion's estimate").optional().steps();
  b.inputs("cloud", &Ports::cloud).doc("a LiDAR's frames, in its sensor's frame (cloud0 to cloud3)").required_first(0).depth(4).steps();
  b.input("path", &Ports::path).doc("the planner's path").optional().depth(4).steps();
  b.input("obstacles", &Ports::obstacles).doc("the obstacles a frame found").optional().depth(4).steps();
  b.input("imu", &Ports::imu).doc("the IMU").optional().steps();
  b.inputs("gnss", &Ports::gnss).doc("a receiver's fixes (gnss0, gnss1)").required_first(0).steps();
  b.output("odom", &Ports::odom).doc("nav_msgs/Odometry: the car in the map, its speed and yaw rate").type_from("odom_type");
  b.output("pose", &Ports::pose).doc("geometry_msgs/PoseStamped: the car in the map").type_from("pose_type");
  b.output("tf", &Ports::tf).doc("tf2_msgs/TFMessage: map to base; base to each cloud's sensor").type_from("tf_type");
  b.output("points", &Ports::points).doc("sensor_msgs/PointCloud2: every cloud input's, in its sensor's frame").type_from("points_type");
  b.output("path_markers", &Ports::path_markers).doc("visualization_msgs/MarkerArray: the path as a line strip").type_from("markers_type");
  b.output("obstacle_markers", &Ports::obstacle_markers).doc("visualization_msgs/MarkerArray: the obstacles as boxes").type_from("markers_type");
  b.output("imu_data", &Ports::imu_data).doc("sensor_msgs/Imu: the IMU (no orientation)").type_from("imu_type");
  b.output("fix", &Ports::fix).doc("sensor_msgs/NavSatFix: every gnss input's fixes, about the datum").type_from("fix_type");
  return b;
}

class Bridge : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("ros2.bridge", "1.0.0")
        .describe("the car in ROS 2's standard messages: Odometry, PoseStamped, tf, PointCloud2, MarkerArray, Imu, NavSatFix")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    frames_ = s.frames;
    io_ = ports().connect(ctx);
    if (s.datum_latitude && s.datum_longitude) datum_.emplace(drivers::Datum{*s.datum_latitude, *s.datum_longitude, s.datum_altitude});
    for (const auto& in : io_.gnss)
      if (in.connected() && !datum_) throw BadInput("parameters 'datum_latitude' and 'datum_longitude': a gnss input is wired, its fixes are placed about them");
  }

  void step(Context&) override {
    for (const auto& e : io_.estimate.take()) publish_estimate(*e);
    for (auto& in : io_.cloud)
      for (const auto& c : in.take()) publish_cloud(*c);
    for (const auto& p : io_.path.take()) send(io_.path_markers, [&](auto& out) { cdr::write_marker_array(ros2::path_markers(*p, frames_), out); });
    for (const auto& o : io_.obstacles.take())
      send(io_.obstacle_markers, [&](auto& out) { cdr::write_marker_array(ros2::obstacle_markers(*o, frames_), out); });
    for (auto& in : io_.gnss)
      for (const auto& f : in.take()) {
        ros2::navsatfix_values(*f, *datum_, frames_, fix_);
        send(io_.fix, [&](auto& out) { cdr::write_navsatfix(fix_, out); });
      }
    for (const auto& m : io_.imu.take()) {
      ros2::imu_values(*m, frames_, imu_);
      send(io_.imu_data, [&](auto& out) { cdr::write_imu(imu_, out); });
    }
  }

  void deactivate(Context& ctx) override { ctx.metric("published", static_cast<double>(published_)); }

 private:
  void publish_estimate(const msgs::LocalizationEstimate& e) {
    const cdr::Ros2Odometry odom = ros2::odometry(e, frames_);
    send(io_.odom, [&](auto& out) { cdr::write_odometry(odom, out); });
    send(io_.pose, [&](auto& out) { cdr::write_pose_stamped(odom.stamp_ns, odom.frame_id, odom.pose, out); });
    send(io_.tf, [&](auto& out) { cdr::write_tf_message({ros2::map_to_base(e, frames_)}, out); });
  }

  void publish_cloud(const msgs::PointCloud& c) {
    ros2::cloud_columns(c, frames_, cloud_);
    send(io_.points, [&](auto& out) { cdr::write_pointcloud2(cloud_, out); });
    send(io_.tf, [&](auto& out) { cdr::write_tf_message({ros2::base_to_sensor(c, frames_)}, out); });
  }

  // A sample written as its CDR and published (readers keep the object: a fresh one each time).
  template <class Write> void send(AnyOutput& port, Write write) {
    SerializedSample s;
    write(s.cdr);
    port.publish(std::move(s));
    ++published_;
  }

  ros2::Frames frames_;
  cdr::CloudColumns cloud_;
  cdr::ImuValues imu_;
  cdr::NavSatFixValues fix_;
  std::optional<drivers::LocalDatum> datum_;
  std::uint64_t published_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Bridge)
