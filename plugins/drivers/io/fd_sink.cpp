// A descriptor written without blocking, for a tty (serial://) and a pty's master (pty_sink).
#include "transports.hpp"

#include <unistd.h>

#include <cerrno>
#include <string>
#include <utility>

namespace brickyard::drivers {
namespace {

class FdSink final : public ByteSink {
 public:
  FdSink(UniqueFd fd, std::string name) : fd_(std::move(fd)), name_(std::move(name)) {}

  // What the kernel does not take at once is dropped, not kept for later: a later send must not
  // block or grow without bound. A message cut so reads as truncated to the decoders, as it would
  // from a device whose port overflowed.
  bool send(const uint8_t* data, size_t size) override {
    if (!error_.empty()) return false;
    size_t sent = 0;
    while (sent < size) {
      ssize_t n = ::write(fd_.get(), data + sent, size - sent);
      if (n > 0) {
        sent += static_cast<size_t>(n);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n == 0 || errno == EAGAIN || errno == EWOULDBLOCK) break;
      error_ = device_error(name_, "write failed", errno);
      return false;
    }
    dropped_ += size - sent;
    return true;
  }

  const std::string& error() const override { return error_; }
  uint64_t dropped() const override { return dropped_; }

 private:
  UniqueFd fd_;
  std::string name_;
  std::string error_;
  uint64_t dropped_ = 0;
};

}  // namespace

std::unique_ptr<ByteSink> make_fd_sink(UniqueFd fd, std::string name) {
  return std::make_unique<FdSink>(std::move(fd), std::move(name));
}

}  // namespace brickyard::drivers
