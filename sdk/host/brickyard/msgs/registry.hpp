#pragma once
// Every message type of the SDK by name: how the host builds a DDS topic for a port.
// Host-only (target brickyard::msgs_dds, in sdk/host/): not installed, never seen by a plugin.
#include <cstddef>

namespace eprosima::fastdds::dds { class TopicDataType; }

namespace brickyard::msgs {

struct TypeEntry {
  const char* name;   // "brickyard::msgs::GnssFix"
  const char* hash;   // hash of the IDL text, as in message_traits<T>::hash
  eprosima::fastdds::dds::TopicDataType* (*make)();  // new type support; caller owns it
};

const TypeEntry* find_type(const char* name);
const TypeEntry* all_types(std::size_t* count);

}  // namespace brickyard::msgs
