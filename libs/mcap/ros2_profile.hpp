#pragma once
// A Brickyard recording in MCAP's "ros2" profile (`brickyard run --record FILE.mcap
// --record-profile ros2`, docs/recording.md) names its channels and schemas as a ROS 2 bag does:
// the wire "node.port" is the topic "/brickyard/node/port", the type "brickyard::msgs::Imu" the
// schema "brickyard_msgs/msg/Imu" (encoding "ros2msg", the message package's definitions;
// docs/ros2.md), the messages the same CDR. Our readers take either profile by these maps.
// Framework-free.
#include <string>
#include <utility>

namespace brickyard::mcap {

inline constexpr const char* kRos2Package = "brickyard_msgs";

// "node.port" -> "/brickyard/node/port".
std::string ros2_topic_name(const std::string& topic);
// "brickyard::msgs::Imu" -> "brickyard_msgs/msg/Imu".
std::string ros2_schema_name(const std::string& type);
// A channel's (topic, type) as Brickyard names them: a ros2msg schema of our package's, and its
// channel under /brickyard/, mapped back; anything else as it is.
std::pair<std::string, std::string> brickyard_names(const std::string& topic, const std::string& schema_name,
                                                    const std::string& schema_encoding);

}  // namespace brickyard::mcap
