#pragma once
// Every type a wire can carry, by name: the SDK's messages (their generated type support) and
// ROS 2's standard types (cdr/ros2_std_types.hpp), which the host carries as the CDR a plugin
// wrote (Manifest::output_any), never decoding them: their sample object is a SerializedSample.
#include <brickyard/msgs/registry.hpp>

#include <string>

namespace brickyard::fw {

// Null when no type of that name is known.
const msgs::TypeEntry* find_wire_type(const std::string& type);

// A ROS 2 standard type: its samples are SerializedSample objects, whatever reads them.
bool is_ros2_standard_type(const std::string& type);

}  // namespace brickyard::fw
