// The ROS 2 message package from IDL (cdr/ros2_msgs.hpp): each IDL type as the ROS 2 type with the
// same CDR, bounds kept, structs by package; names ROS 2 does not allow and types it has no form
// for refused, named.
#include "cdr/ros2_msgs.hpp"
#include "cdr/ros2_std_types.hpp"
#include "mcap/ros2_profile.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>

using namespace brickyard::cdr;

namespace {
const char* kIdl = R"(
module brickyard { module msgs {
struct Inner { double x; };
struct Outer {
  boolean ok; octet raw; int8 a; uint8 b; int16 c; uint16 d; int32 e; uint32 f; int64 g; uint64 h; float i; double j;
  string name; string<8> tag;
  sequence<float> xs; sequence<uint8, 64> data; double pose[3];
  Inner one; sequence<Inner> many; brickyard::msgs::Inner qualified;
};
}; };
)";

std::string file_text(const std::vector<Ros2File>& files, const std::string& path) {
  for (const auto& f : files)
    if (f.path == path) return f.text;
  return "";
}

std::vector<Ros2File> package_of(const std::string& idl) {
  Ros2PackageInfo info;
  info.version = "1.0.0";
  return ros2_package(parse_idl(idl), info);
}
}  // namespace

TEST(Ros2Msgs, EachTypeIsTheRos2TypeOfTheSameCdr) {
  const auto files = package_of(kIdl);
  EXPECT_EQ(file_text(files, "msg/Inner.msg").substr(file_text(files, "msg/Inner.msg").find('\n') + 1), "float64 x\n");
  const std::string outer = file_text(files, "msg/Outer.msg");
  EXPECT_EQ(outer.substr(outer.find('\n') + 1),
            "bool ok\nbyte raw\nint8 a\nuint8 b\nint16 c\nuint16 d\nint32 e\nuint32 f\nint64 g\nuint64 h\nfloat32 i\nfloat64 j\n"
            "string name\nstring<=8 tag\nfloat32[] xs\nuint8[<=64] data\nfloat64[3] pose\n"
            "brickyard_msgs/Inner one\nbrickyard_msgs/Inner[] many\nbrickyard_msgs/Inner qualified\n");
  const std::string cmake = file_text(files, "CMakeLists.txt");
  EXPECT_NE(cmake.find("rosidl_generate_interfaces(${PROJECT_NAME}\n  \"msg/Inner.msg\"\n  \"msg/Outer.msg\"\n)"), std::string::npos) << cmake;
  const std::string xml = file_text(files, "package.xml");
  EXPECT_NE(xml.find("<name>brickyard_msgs</name>"), std::string::npos);
  EXPECT_NE(xml.find("<version>1.0.0</version>"), std::string::npos);
  EXPECT_NE(xml.find("<member_of_group>rosidl_interface_packages</member_of_group>"), std::string::npos);
}

TEST(Ros2Msgs, WhatRos2CannotNameIsRefusedNamed) {
  auto refused = [](const std::string& idl, const std::string& what) {
    try {
      package_of(idl);
      ADD_FAILURE() << "accepted: " << idl;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused("module m { struct lower { double x; }; };", "struct m::lower: not a ROS 2 type name (CamelCase)");
  refused("module m { struct A { double X; }; };", "struct A: member 'X' is not a ROS 2 field name");
  refused("module m { struct A { double a__b; }; };", "member 'a__b'");
  refused("module m { struct A { char c; }; };", "struct A, member 'c': type 'char' has no ROS 2 twin");
  refused("module m { struct A { sequence<sequence<double>> s; }; };", "a sequence of sequences or arrays has no ROS 2 form");
  refused("module m { struct A { double x; }; }; module n { struct B { double y; }; };", "struct n::B: not in module m");
}

// The same structs in IDL as ROS 2's DDS middlewares name them on the wire: module
// PACKAGE::msg::dds_, each type TYPE_, a struct member by its dds_ name, bounds and arrays kept;
// extensibility said (final, as ours and ROS 2's are); the IDL reader takes it back with the same
// members; ROS 2's refusals the same.
TEST(Ros2Msgs, TheDdsIdlNamesTypesAsRos2MiddlewaresDo) {
  Ros2PackageInfo info;
  info.version = "1.0.0";
  const std::string idl = ros2_dds_idl(parse_idl(kIdl), info);
  std::string plain = idl;  // our IDL reader's subset has no annotations
  for (std::size_t at; (at = plain.find("@final ")) != std::string::npos;) plain.erase(at, 7);
  const IdlModel back = parse_idl(plain);
  ASSERT_EQ(back.defined, (std::vector<std::string>{"brickyard_msgs::msg::dds_::Inner_", "brickyard_msgs::msg::dds_::Outer_"}));
  EXPECT_NE(idl.find("@final struct Outer_ {"), std::string::npos) << idl;
  for (const char* member : {"  uint8 b;", "  string<8> tag;", "  sequence<float> xs;", "  sequence<uint8, 64> data;", "  double pose[3];",
                             "  Inner_ one;", "  sequence<Inner_> many;", "  Inner_ qualified;"})
    EXPECT_NE(idl.find(member), std::string::npos) << member << " in\n" << idl;
  const auto& outer = *back.structs.at("brickyard_msgs::msg::dds_::Outer_");
  const IdlModel source = parse_idl(kIdl);
  const auto& original = *source.structs.at("brickyard::msgs::Outer");
  ASSERT_EQ(outer.size(), original.size());
  for (std::size_t i = 0; i < outer.size(); ++i) {
    EXPECT_EQ(outer[i].name, original[i].name);
    EXPECT_EQ(outer[i].type.kind, original[i].type.kind) << outer[i].name;
    EXPECT_EQ(outer[i].type.bound, original[i].type.bound) << outer[i].name;
    EXPECT_EQ(outer[i].type.size, original[i].type.size) << outer[i].name;
  }
  EXPECT_THROW(ros2_dds_idl(parse_idl("module m { struct A { double X; }; };"), info), std::invalid_argument);
}

// A type's ros2msg schema (a ROS 2 bag's): its .msg text, then every struct it uses, each once,
// after a line of 80 '=' and "MSG: PACKAGE/Type", as @foxglove/rosmsg parses them.
TEST(Ros2Msgs, ARos2msgSchemaHoldsItsTypeThenEveryTypeItUses) {
  const std::string schema = ros2msg_schema(parse_idl(kIdl), "brickyard::msgs::Outer", "brickyard_msgs");
  const std::string separator = "\n" + std::string(80, '=') + "\nMSG: brickyard_msgs/Inner\n";
  const auto at = schema.find(separator);
  ASSERT_NE(at, std::string::npos) << schema;
  EXPECT_EQ(schema.find(separator, at + 1), std::string::npos) << "Inner once, though Outer uses it three times";
  EXPECT_EQ(schema.rfind("# Outer:", 0), 0u) << schema;
  EXPECT_NE(schema.find("brickyard_msgs/Inner[] many\n"), std::string::npos);
  EXPECT_EQ(schema.substr(at + separator.size()).rfind("# Inner:", 0), 0u);
  EXPECT_NE(schema.find("float64 x\n", at), std::string::npos);
  EXPECT_THROW(ros2msg_schema(parse_idl(kIdl), "brickyard::msgs::Missing", "brickyard_msgs"), std::invalid_argument);
}

// A recording's names in MCAP's ros2 profile, and back: node.port is /brickyard/node/port, our
// types brickyard_msgs/msg/T (ros2msg); anything else (another profile's, another package's, a
// topic not ours) is left as it is.
TEST(Ros2Profile, NamesGoToRos2AndBack) {
  using namespace brickyard::mcap;
  EXPECT_EQ(ros2_topic_name("estimator.estimate"), "/brickyard/estimator/estimate");
  EXPECT_EQ(ros2_schema_name("brickyard::msgs::Imu"), "brickyard_msgs/msg/Imu");
  EXPECT_EQ(brickyard_names("/brickyard/estimator/estimate", "brickyard_msgs/msg/LocalizationEstimate", "ros2msg"),
            std::make_pair(std::string("estimator.estimate"), std::string("brickyard::msgs::LocalizationEstimate")));
  EXPECT_EQ(brickyard_names("estimator.estimate", "brickyard::msgs::LocalizationEstimate", "omgidl"),
            std::make_pair(std::string("estimator.estimate"), std::string("brickyard::msgs::LocalizationEstimate")));
  EXPECT_EQ(brickyard_names("/points", "sensor_msgs/msg/PointCloud2", "ros2msg"),
            std::make_pair(std::string("/points"), std::string("sensor_msgs/msg/PointCloud2")));
  EXPECT_EQ(brickyard_names("/a/b/c", "brickyard_msgs/msg/Imu", "ros2msg").first, "/a/b/c");
}

// A Brickyard port of a ROS 2 standard type (the bridge's, cdr/ros2_std_types.hpp) on our topics:
// its schema keeps ROS 2's name, and reads back as our qualified one.
TEST(Ros2Profile, StandardTypesOnOurTopicsGoToRos2AndBack) {
  using namespace brickyard::mcap;
  EXPECT_EQ(ros2_schema_name("nav_msgs::msg::Odometry"), "nav_msgs/msg/Odometry");
  EXPECT_EQ(ros2_schema_name("a::b::C"), "a::b::C");
  EXPECT_EQ(brickyard_names("/brickyard/bridge/odom", "nav_msgs/msg/Odometry", "ros2msg"),
            std::make_pair(std::string("bridge.odom"), std::string("nav_msgs::msg::Odometry")));
}

// ROS 2 Humble's standard types as IDL: each parses, and its ros2msg schema names every struct by
// its own package, as a ROS 2 bag's does (what Foxglove's and ROS 2's readers look types up by).
TEST(Ros2StandardTypes, EachParsesAndItsSchemaNamesEachStructByItsPackage) {
  for (const std::string& t : ros2_standard_types()) {
    const char* idl = ros2_standard_idl(t);
    ASSERT_NE(idl, nullptr) << t;
    const IdlModel model = parse_idl(self_contained_idl(idl));
    EXPECT_TRUE(model.structs.count(t)) << t;
  }
  EXPECT_EQ(ros2_standard_idl("nav_msgs::msg::Path"), nullptr) << "not one of those written";
  const std::string odom = ros2msg_schema(parse_idl(self_contained_idl(ros2_standard_idl("nav_msgs::msg::Odometry"))), "nav_msgs::msg::Odometry", "brickyard_msgs");
  EXPECT_EQ(odom.rfind("std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n", 0), 0u) << odom;
  for (const char* section : {"MSG: std_msgs/Header\n", "MSG: builtin_interfaces/Time\n", "MSG: geometry_msgs/PoseWithCovariance\n",
                              "MSG: geometry_msgs/Pose\n", "MSG: geometry_msgs/Point\n", "MSG: geometry_msgs/Quaternion\n",
                              "MSG: geometry_msgs/TwistWithCovariance\n", "MSG: geometry_msgs/Twist\n", "MSG: geometry_msgs/Vector3\n"})
    EXPECT_NE(odom.find(section), std::string::npos) << section << odom;
  EXPECT_NE(odom.find("float64[36] covariance\n"), std::string::npos);
  EXPECT_EQ(odom.find("brickyard"), std::string::npos) << "no line of ours in ROS 2's own definitions";
  const std::string markers = ros2msg_schema(parse_idl(self_contained_idl(ros2_standard_idl("visualization_msgs::msg::MarkerArray"))),
                                             "visualization_msgs::msg::MarkerArray", "brickyard_msgs");
  EXPECT_NE(markers.find("builtin_interfaces/Duration lifetime\n"), std::string::npos) << markers;
  EXPECT_NE(markers.find("MSG: sensor_msgs/CompressedImage\n"), std::string::npos);
}
