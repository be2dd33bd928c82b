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
  if (type.rfind(kModule, 0) != 0) return type;
  return kSchemaRoot + type.substr(kModule.size());
}

std::pair<std::string, std::string> brickyard_names(const std::string& topic, const std::string& schema_name,
                                                    const std::string& schema_encoding) {
  if (schema_encoding != "ros2msg" || schema_name.rfind(kSchemaRoot, 0) != 0) return {topic, schema_name};
  std::string ours = topic;
  if (topic.rfind(kTopicRoot, 0) == 0) {
    ours = topic.substr(kTopicRoot.size());
    const auto slash = ours.find('/');
    if (slash != std::string::npos && ours.find('/', slash + 1) == std::string::npos) ours[slash] = '.';
    else ours = topic;
  }
  return {ours, kModule + schema_name.substr(kSchemaRoot.size())};
}

}  // namespace brickyard::mcap
