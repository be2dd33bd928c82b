#pragma once
// A message object serialized as on the wire (CDR, with its encapsulation header), by its type's
// Fast DDS type support: what the recorder writes and the live server sends. One per output
// port (a node publishes from one thread at a time); the bytes stay valid until the next call.
#include <cstddef>
#include <memory>
#include <string>

namespace eprosima::fastdds::dds { class TopicDataType; }
namespace eprosima::fastrtps::rtps { struct SerializedPayload_t; }

namespace brickyard::fw {

class SampleSerializer {
 public:
  explicit SampleSerializer(const std::string& type);  // throws std::runtime_error: no type support
  ~SampleSerializer();
  SampleSerializer(const SampleSerializer&) = delete;
  SampleSerializer& operator=(const SampleSerializer&) = delete;

  struct Bytes {
    const unsigned char* data;
    std::size_t size;
  };
  // Throws std::runtime_error when the type support cannot serialize it.
  Bytes serialize(const void* message);
  const std::string& type() const { return type_; }

 private:
  std::string type_;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support_;
  std::unique_ptr<eprosima::fastrtps::rtps::SerializedPayload_t> payload_;
};

}  // namespace brickyard::fw
