#pragma once
// A ROS 2 message package from message definitions in IDL (issue 45): each struct a `.msg` file
// that ROS 2's rosidl builds, its members in order and each type the one ROS 2's IDL mapping
// gives the same CDR for (double float64, uint8 uint8, int16 int16, sequence<T> T[],
// sequence<T, N> T[<=N], T name[N] T[N], a struct PACKAGE/Type), so that a ROS 2 node's message of
// the package and Brickyard's sample are the same bytes. With its package.xml and CMakeLists.txt
// (ament_cmake, rosidl_default_generators) a colcon workspace builds it. Framework-free.
#include "cdr/idl_model.hpp"

#include <string>
#include <vector>

namespace brickyard::cdr {

struct Ros2File {
  std::string path;  // relative to the package's folder: "msg/Imu.msg", "package.xml", "CMakeLists.txt"
  std::string text;
};

struct Ros2PackageInfo {
  std::string name = "brickyard_msgs";
  std::string version;      // the SDK's, "1.2.0"
  std::string description;
  std::string maintainer = "Brickyard", maintainer_email = "brickyard@localhost";
  std::string license = "Apache-2.0";
};

// Every struct of `model` (each qualified name once, in the order defined), as the package's
// files. Throws std::invalid_argument naming the struct, member or type ROS 2 has no form for: a
// name ROS 2 does not allow (a type not CamelCase, a member not lower_snake_case), a primitive
// type without a ROS 2 twin, a struct of another module than the first's.
std::vector<Ros2File> ros2_package(const IdlModel& model, const Ros2PackageInfo& info);

// The same structs as ROS 2's DDS middlewares (rmw_fastrtps, rmw_cyclonedds) name them on the wire,
// in OMG IDL: module PACKAGE::msg::dds_, each struct TYPE_ (its members and their IDL types as in
// `model`, a struct member by its dds_ name). A DDS program of any vendor compiled from it (Cyclone
// DDS's idlc) reads and writes a graph with transport.naming "ros2" without ROS 2. The same
// refusals as ros2_package.
std::string ros2_dds_idl(const IdlModel& model, const Ros2PackageInfo& info);

// One type's definition as a ROS 2 bag's "ros2msg" schema carries it: its .msg text, then each
// struct it uses (in the order first met, each once) after a line of 80 '=' and "MSG: PACKAGE/Type".
// `qualified` must be a struct of `model`; the same refusals as ros2_package.
std::string ros2msg_schema(const IdlModel& model, const std::string& qualified, const std::string& package);

// One member's ROS 2 type: "float64", "uint8[<=64]", "brickyard_msgs/Header[]".
std::string ros2_type(const IdlType& t, const std::string& package);

}  // namespace brickyard::cdr
