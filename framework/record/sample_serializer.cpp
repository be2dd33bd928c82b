#include "record/sample_serializer.hpp"

#include "transport/wire_types.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <stdexcept>

namespace brickyard::fw {

SampleSerializer::SampleSerializer(const std::string& type)
    : type_(type), payload_(std::make_unique<eprosima::fastrtps::rtps::SerializedPayload_t>()) {
  const auto* entry = find_wire_type(type);
  if (!entry) throw std::runtime_error("no type support for " + type);
  support_.reset(entry->make());
}

SampleSerializer::~SampleSerializer() = default;

SampleSerializer::Bytes SampleSerializer::serialize(const void* message) {
  void* data = const_cast<void*>(message);  // serialize() reads only; its signature predates const
  const std::uint32_t size = support_->getSerializedSizeProvider(data)();
  if (payload_->max_size < size) payload_->reserve(size);
  payload_->length = 0;
  payload_->pos = 0;
  if (!support_->serialize(data, payload_.get())) throw std::runtime_error("serializing a sample of " + type_);
  return {payload_->data, payload_->length};
}

}  // namespace brickyard::fw
