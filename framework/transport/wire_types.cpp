#include "transport/wire_types.hpp"

#include "cdr/ros2_std_types.hpp"

#include <brickyard/context.hpp>

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>
#include <map>

namespace brickyard::fw {

namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// A type whose sample is its CDR, encapsulation header first (SerializedSample): written and read
// as it is. Without a key (one instance), as every Brickyard type.
class RawCdrType : public eprosima::fastdds::dds::TopicDataType {
 public:
  RawCdrType() {
    setName("brickyard::RawCdr");  // registered under the wire's own type name (transport/dds.cpp)
    m_typeSize = 4096;             // a first allocation: samples grow it (PREALLOCATED_WITH_REALLOC)
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, SerializedPayload_t* payload) override {
    const auto& cdr = static_cast<const SerializedSample*>(data)->cdr;
    if (cdr.size() < 4 || payload->max_size < cdr.size()) return false;
    std::memcpy(payload->data, cdr.data(), cdr.size());
    payload->length = static_cast<std::uint32_t>(cdr.size());
    payload->encapsulation = cdr[1] == 0x01 ? CDR_LE : CDR_BE;
    return true;
  }
  bool deserialize(SerializedPayload_t* payload, void* data) override {
    auto& cdr = static_cast<SerializedSample*>(data)->cdr;
    cdr.assign(payload->data, payload->data + payload->length);
    return payload->length >= 4;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data]() { return static_cast<std::uint32_t>(static_cast<const SerializedSample*>(data)->cdr.size()); };
  }
  void* createData() override { return new SerializedSample(); }
  void deleteData(void* data) override { delete static_cast<SerializedSample*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

eprosima::fastdds::dds::TopicDataType* make_raw() { return new RawCdrType(); }

}  // namespace

bool is_ros2_standard_type(const std::string& type) { return cdr::ros2_standard_idl(type) != nullptr; }

const msgs::TypeEntry* find_wire_type(const std::string& type) {
  if (const auto* entry = msgs::find_type(type.c_str())) return entry;
  static const std::map<std::string, msgs::TypeEntry> standard = [] {
    std::map<std::string, msgs::TypeEntry> m;
    // Their hash names the definitions: ROS 2 Humble's (cdr/ros2_std_types.hpp).
    for (const std::string& t : cdr::ros2_standard_types()) m.emplace(t, msgs::TypeEntry{nullptr, "ros2-humble", &make_raw});
    for (auto& [name, entry] : m) entry.name = name.c_str();
    return m;
  }();
  const auto it = standard.find(type);
  return it == standard.end() ? nullptr : &it->second;
}

}  // namespace brickyard::fw
