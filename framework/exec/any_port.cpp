// An output of any type (Manifest::output_any): what its plugin publishes as CDR, decoded by the
// readers' type's Fast DDS type support into the object typed readers take.
#include "exec/channels.hpp"

#include "transport/wire_types.hpp"

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>
#include <stdexcept>

namespace brickyard::fw {

void OutputPort::make_any(std::string type, std::string idl) {
  any_ = true;
  wire_type_ = std::move(type);
  wire_idl_ = std::move(idl);
  if (wire_type_.empty()) return;
  const auto* entry = find_wire_type(wire_type_);
  if (!entry) throw std::runtime_error(name_ + ": no type support for " + wire_type_);
  support_.reset(entry->make());
}

std::shared_ptr<const void> OutputPort::decode_any(const SerializedSample& s) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(s.cdr.size()));
  if (!s.cdr.empty()) std::memcpy(payload.data, s.cdr.data(), s.cdr.size());
  payload.length = static_cast<std::uint32_t>(s.cdr.size());
  void* m = support_->createData();
  if (!support_->deserialize(&payload, m)) {
    support_->deleteData(m);
    throw std::runtime_error("output '" + name_ + "': a published sample does not decode as " + wire_type_);
  }
  auto support = support_;
  return std::shared_ptr<const void>(m, [support](const void* p) { support->deleteData(const_cast<void*>(p)); });
}

}  // namespace brickyard::fw
