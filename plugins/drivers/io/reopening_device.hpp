#pragma once
// A live device that is opened again after it fails. A receiver that
// reboots closes its TCP port, a USB serial adapter shaken loose comes back as the same tty: a
// driver that gave up on the first failure would leave the car without that sensor for the rest
// of the race. Every `retry_s` of the run's clock after a failure the device is opened anew (the
// spec as at the start); until then, and while an open fails, the failure is what error() says.
#include "byte_source.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::drivers {

class ReopeningDevice {
 public:
  // Opens it; throws std::runtime_error naming the device when it cannot (at the start a wrong
  // device is a wrong graph: exit 2). retry_s <= 0: a failed device stays failed.
  ReopeningDevice(const SourceSpec& spec, double retry_s);

  // What arrived, as ByteSource::poll; false while failed (error() says why).
  bool poll(int64_t now_ns, std::vector<std::vector<uint8_t>>& out, size_t max_bytes);
  // The receive time of each entry the last poll appended (ByteSource::arrivals_ns).
  const std::vector<int64_t>& arrivals_ns() const;
  // The failure, empty while the device is open.
  const std::string& error() const { return error_; }
  int fd() const { return device_ ? device_->fd() : -1; }
  bool reopens() const { return retry_ns_ > 0; }
  uint64_t reopened() const { return reopened_; }  // opens that worked after a failure
  uint64_t failures() const { return failures_; }

 private:
  void fail(int64_t now_ns, std::string why);
  void try_reopen(int64_t now_ns);

  SourceSpec spec_;
  int64_t retry_ns_;
  std::unique_ptr<ByteSource> device_;
  std::string error_;
  int64_t failed_ns_ = 0;  // of the failure or the last open tried
  uint64_t reopened_ = 0, failures_ = 0;
};

}  // namespace brickyard::drivers
