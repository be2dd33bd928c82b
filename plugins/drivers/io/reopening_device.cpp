#include "reopening_device.hpp"

#include <stdexcept>

namespace brickyard::drivers {

ReopeningDevice::ReopeningDevice(const SourceSpec& spec, double retry_s)
    : spec_(spec), retry_ns_(static_cast<int64_t>(retry_s * 1e9)) {
  std::string error;
  device_ = open_source(spec_, error);
  if (!device_) throw std::runtime_error(error);
}

bool ReopeningDevice::poll(int64_t now_ns, std::vector<std::vector<uint8_t>>& out, size_t max_bytes) {
  if (!device_) try_reopen(now_ns);
  if (!device_) return false;
  if (device_->poll(out, max_bytes)) return true;
  fail(now_ns, device_->error());
  return false;
}

const std::vector<int64_t>& ReopeningDevice::arrivals_ns() const {
  static const std::vector<int64_t> none;
  return device_ ? device_->arrivals_ns() : none;
}

void ReopeningDevice::fail(int64_t now_ns, std::string why) {
  // What the last poll read before the failure is kept by the caller; the descriptor goes now,
  // so a waiter on it is not woken without end.
  device_.reset();
  error_ = std::move(why);
  failed_ns_ = now_ns;
  ++failures_;
}

void ReopeningDevice::try_reopen(int64_t now_ns) {
  if (retry_ns_ <= 0 || now_ns - failed_ns_ < retry_ns_) return;
  failed_ns_ = now_ns;
  std::string error;
  std::unique_ptr<ByteSource> fresh = open_source(spec_, error);
  if (!fresh) {
    error_ = std::move(error);
    return;
  }
  device_ = std::move(fresh);
  error_.clear();
  ++reopened_;
}

}  // namespace brickyard::drivers
