#include "cdr/ros2_std_types.hpp"

#include <map>

namespace brickyard::cdr {

namespace {

// One struct: its qualified name, the structs it uses and its module block.
struct Definition {
  const char* name;
  std::vector<const char*> uses;
  const char* idl;
};

// ROS 2 Humble's definitions, member for member (rosidl's IDL mapping: float64 double, byte and
// uint8[] sequence<uint8>, T[N] an array, T[] a sequence).
const std::vector<Definition>& definitions() {
  static const std::vector<Definition> d = {
      {"builtin_interfaces::msg::Time", {}, "module builtin_interfaces { module msg {\nstruct Time {\n  int32 sec;\n  uint32 nanosec;\n};\n}; };\n"},
      {"builtin_interfaces::msg::Duration", {}, "module builtin_interfaces { module msg {\nstruct Duration {\n  int32 sec;\n  uint32 nanosec;\n};\n}; };\n"},
      {"std_msgs::msg::Header", {"builtin_interfaces::msg::Time"},
       "module std_msgs { module msg {\nstruct Header {\n  builtin_interfaces::msg::Time stamp;\n  string frame_id;\n};\n}; };\n"},
      {"std_msgs::msg::ColorRGBA", {}, "module std_msgs { module msg {\nstruct ColorRGBA {\n  float r;\n  float g;\n  float b;\n  float a;\n};\n}; };\n"},
      {"geometry_msgs::msg::Point", {}, "module geometry_msgs { module msg {\nstruct Point {\n  double x;\n  double y;\n  double z;\n};\n}; };\n"},
      {"geometry_msgs::msg::Vector3", {}, "module geometry_msgs { module msg {\nstruct Vector3 {\n  double x;\n  double y;\n  double z;\n};\n}; };\n"},
      {"geometry_msgs::msg::Quaternion", {},
       "module geometry_msgs { module msg {\nstruct Quaternion {\n  double x;\n  double y;\n  double z;\n  double w;\n};\n}; };\n"},
      {"geometry_msgs::msg::Pose", {"geometry_msgs::msg::Point", "geometry_msgs::msg::Quaternion"},
       "module geometry_msgs { module msg {\nstruct Pose {\n  geometry_msgs::msg::Point position;\n  geometry_msgs::msg::Quaternion orientation;\n};\n}; };\n"},
      {"geometry_msgs::msg::PoseWithCovariance", {"geometry_msgs::msg::Pose"},
       "module geometry_msgs { module msg {\nstruct PoseWithCovariance {\n  geometry_msgs::msg::Pose pose;\n  double covariance[36];\n};\n}; };\n"},
      {"geometry_msgs::msg::Twist", {"geometry_msgs::msg::Vector3"},
       "module geometry_msgs { module msg {\nstruct Twist {\n  geometry_msgs::msg::Vector3 linear;\n  geometry_msgs::msg::Vector3 angular;\n};\n}; };\n"},
      {"geometry_msgs::msg::TwistWithCovariance", {"geometry_msgs::msg::Twist"},
       "module geometry_msgs { module msg {\nstruct TwistWithCovariance {\n  geometry_msgs::msg::Twist twist;\n  double covariance[36];\n};\n}; };\n"},
      {"geometry_msgs::msg::Transform", {"geometry_msgs::msg::Vector3", "geometry_msgs::msg::Quaternion"},
       "module geometry_msgs { module msg {\nstruct Transform {\n  geometry_msgs::msg::Vector3 translation;\n  geometry_msgs::msg::Quaternion rotation;\n};\n}; };\n"},
      {"geometry_msgs::msg::TransformStamped", {"std_msgs::msg::Header", "geometry_msgs::msg::Transform"},
       "module geometry_msgs { module msg {\nstruct TransformStamped {\n  std_msgs::msg::Header header;\n  string child_frame_id;\n"
       "  geometry_msgs::msg::Transform transform;\n};\n}; };\n"},
      {"geometry_msgs::msg::PoseStamped", {"std_msgs::msg::Header", "geometry_msgs::msg::Pose"},
       "module geometry_msgs { module msg {\nstruct PoseStamped {\n  std_msgs::msg::Header header;\n  geometry_msgs::msg::Pose pose;\n};\n}; };\n"},
      {"nav_msgs::msg::Odometry", {"std_msgs::msg::Header", "geometry_msgs::msg::PoseWithCovariance", "geometry_msgs::msg::TwistWithCovariance"},
       "module nav_msgs { module msg {\nstruct Odometry {\n  std_msgs::msg::Header header;\n  string child_frame_id;\n"
       "  geometry_msgs::msg::PoseWithCovariance pose;\n  geometry_msgs::msg::TwistWithCovariance twist;\n};\n}; };\n"},
      {"tf2_msgs::msg::TFMessage", {"geometry_msgs::msg::TransformStamped"},
       "module tf2_msgs { module msg {\nstruct TFMessage {\n  sequence<geometry_msgs::msg::TransformStamped> transforms;\n};\n}; };\n"},
      {"sensor_msgs::msg::CompressedImage", {"std_msgs::msg::Header"},
       "module sensor_msgs { module msg {\nstruct CompressedImage {\n  std_msgs::msg::Header header;\n  string format;\n  sequence<uint8> data;\n};\n}; };\n"},
      {"visualization_msgs::msg::UVCoordinate", {}, "module visualization_msgs { module msg {\nstruct UVCoordinate {\n  float u;\n  float v;\n};\n}; };\n"},
      {"visualization_msgs::msg::MeshFile", {},
       "module visualization_msgs { module msg {\nstruct MeshFile {\n  string filename;\n  sequence<uint8> data;\n};\n}; };\n"},
      {"visualization_msgs::msg::Marker",
       {"std_msgs::msg::Header", "geometry_msgs::msg::Pose", "geometry_msgs::msg::Vector3", "std_msgs::msg::ColorRGBA",
        "builtin_interfaces::msg::Duration", "geometry_msgs::msg::Point", "sensor_msgs::msg::CompressedImage",
        "visualization_msgs::msg::UVCoordinate", "visualization_msgs::msg::MeshFile"},
       "module visualization_msgs { module msg {\nstruct Marker {\n  std_msgs::msg::Header header;\n  string ns;\n  int32 id;\n  int32 type;\n"
       "  int32 action;\n  geometry_msgs::msg::Pose pose;\n  geometry_msgs::msg::Vector3 scale;\n  std_msgs::msg::ColorRGBA color;\n"
       "  builtin_interfaces::msg::Duration lifetime;\n  boolean frame_locked;\n  sequence<geometry_msgs::msg::Point> points;\n"
       "  sequence<std_msgs::msg::ColorRGBA> colors;\n  string texture_resource;\n  sensor_msgs::msg::CompressedImage texture;\n"
       "  sequence<visualization_msgs::msg::UVCoordinate> uv_coordinates;\n  string text;\n  string mesh_resource;\n"
       "  visualization_msgs::msg::MeshFile mesh_file;\n  boolean mesh_use_embedded_materials;\n};\n}; };\n"},
      {"visualization_msgs::msg::MarkerArray", {"visualization_msgs::msg::Marker"},
       "module visualization_msgs { module msg {\nstruct MarkerArray {\n  sequence<visualization_msgs::msg::Marker> markers;\n};\n}; };\n"},
      {"sensor_msgs::msg::PointField", {},
       "module sensor_msgs { module msg {\nstruct PointField {\n  string name;\n  uint32 offset;\n  uint8 datatype;\n  uint32 count;\n};\n}; };\n"},
      {"sensor_msgs::msg::PointCloud2", {"std_msgs::msg::Header", "sensor_msgs::msg::PointField"},
       "module sensor_msgs { module msg {\nstruct PointCloud2 {\n  std_msgs::msg::Header header;\n  uint32 height;\n  uint32 width;\n"
       "  sequence<sensor_msgs::msg::PointField> fields;\n  boolean is_bigendian;\n  uint32 point_step;\n  uint32 row_step;\n"
       "  sequence<uint8> data;\n  boolean is_dense;\n};\n}; };\n"},
      {"sensor_msgs::msg::Imu", {"std_msgs::msg::Header", "geometry_msgs::msg::Quaternion", "geometry_msgs::msg::Vector3"},
       "module sensor_msgs { module msg {\nstruct Imu {\n  std_msgs::msg::Header header;\n  geometry_msgs::msg::Quaternion orientation;\n"
       "  double orientation_covariance[9];\n  geometry_msgs::msg::Vector3 angular_velocity;\n  double angular_velocity_covariance[9];\n"
       "  geometry_msgs::msg::Vector3 linear_acceleration;\n  double linear_acceleration_covariance[9];\n};\n}; };\n"},
      {"sensor_msgs::msg::NavSatStatus", {}, "module sensor_msgs { module msg {\nstruct NavSatStatus {\n  int8 status;\n  uint16 service;\n};\n}; };\n"},
      {"sensor_msgs::msg::NavSatFix", {"std_msgs::msg::Header", "sensor_msgs::msg::NavSatStatus"},
       "module sensor_msgs { module msg {\nstruct NavSatFix {\n  std_msgs::msg::Header header;\n  sensor_msgs::msg::NavSatStatus status;\n"
       "  double latitude;\n  double longitude;\n  double altitude;\n  double position_covariance[9];\n  uint8 position_covariance_type;\n};\n}; };\n"},
  };
  return d;
}

void compose(const std::string& name, std::string& out) {
  for (const Definition& d : definitions())
    if (name == d.name) {
      out += d.idl;
      for (const char* u : d.uses) compose(u, out);
    }
}

}  // namespace

const std::vector<std::string>& ros2_standard_types() {
  static const std::vector<std::string> t = {"nav_msgs::msg::Odometry", "geometry_msgs::msg::PoseStamped", "tf2_msgs::msg::TFMessage",
                                             "visualization_msgs::msg::MarkerArray", "sensor_msgs::msg::PointCloud2",
                                             "sensor_msgs::msg::Imu", "sensor_msgs::msg::NavSatFix"};
  return t;
}

const char* ros2_standard_idl(const std::string& type) {
  static const std::map<std::string, std::string> texts = [] {
    std::map<std::string, std::string> m;
    for (const std::string& t : ros2_standard_types()) compose(t, m[t]);
    return m;
  }();
  const auto it = texts.find(type);
  return it == texts.end() ? nullptr : it->second.c_str();
}

}  // namespace brickyard::cdr
