#include "mcap/ros2_profile.hpp"

namespace brickyard::mcap {

namespace {
const std::string kTopicRoot = "/brickyard/";
const std::string kSchemaRoot = std::string(kRos2Package) + "/msg/";
const std::string kModule = "brickyard::msgs::";
}  // namespace

std::string ros2_topic_name(const std::string& topic) {
  std::string out = kTopicRoot + topic;
  const auto dot = out.rfind('.');
  if (dot != std::string::npos && dot >= kTopicRoot.size()) out[dot] = '/';
  return out;
}

std::string ros2_schema_name(const std::string& type) {
  if (type.rfind(kModule, 0) == 0) return kSchemaRoot + type.substr(kModule.size());
  // A ROS 2 standard type, "nav_msgs::msg::Odometry": "nav_msgs/msg/Odometry".
  const auto msg = type.find("::msg::");
  if (msg == std::string::npos || type.find("::", msg + 7) != std::string::npos) return type;
  return type.substr(0, msg) + "/msg/" + type.substr(msg + 7);
}

std::pair<std::string, std::string> brickyard_names(const std::string& topic, const std::string& schema_name,
                                                    const std::string& schema_encoding) {
  if (schema_encoding != "ros2msg") return {topic, schema_name};
  const bool our_type = schema_name.rfind(kSchemaRoot, 0) == 0;
  // A standard type on a topic of ours ("/brickyard/bridge/odom", nav_msgs/msg/Odometry): a
  // Brickyard recording's port of such a type (cdr/ros2_std_types.hpp).
  const auto msg = schema_name.find("/msg/");
  if (!our_type && (topic.rfind(kTopicRoot, 0) != 0 || msg == std::string::npos || msg == 0)) return {topic, schema_name};
  std::string ours = topic;
  if (topic.rfind(kTopicRoot, 0) == 0) {
    ours = topic.substr(kTopicRoot.size());
    const auto slash = ours.find('/');
    if (slash != std::string::npos && ours.find('/', slash + 1) == std::string::npos) ours[slash] = '.';
    else ours = topic;
  }
  if (our_type) return {ours, kModule + schema_name.substr(kSchemaRoot.size())};
  return {ours, schema_name.substr(0, msg) + "::msg::" + schema_name.substr(msg + 5)};
}

}  // namespace brickyard::mcap
