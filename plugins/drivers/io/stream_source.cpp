// A stream read without blocking, for tcp and serial: each poll reads until the descriptor has
// nothing more (EAGAIN) or max_bytes have been read, one entry per read.
#include "transports.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::drivers {
namespace {

// One read's largest size: a TCP segment train or a serial port's buffer fits.
constexpr size_t kReadChunk = 64 * 1024;

class StreamSource final : public ByteSource {
 public:
  StreamSource(UniqueFd fd, std::string name, StreamWords words)
      : fd_(std::move(fd)), name_(std::move(name)), words_(words), scratch_(kReadChunk) {}

  bool poll(std::vector<std::vector<uint8_t>>& out, size_t max_bytes) override {
    if (!error_.empty()) return false;
    size_t total = 0;
    while (total < max_bytes) {
      size_t want = std::min(scratch_.size(), max_bytes - total);
      ssize_t n = ::read(fd_.get(), scratch_.data(), want);
      if (n > 0) {
        out.emplace_back(scratch_.begin(), scratch_.begin() + n);
        total += static_cast<size_t>(n);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
      // The device is gone: the descriptor is closed now so a peer sees it at once.
      error_ = n == 0 ? device_error(name_, words_.ended, 0) : device_error(name_, words_.failed, errno);
      fd_.reset();
      return false;
    }
    return true;
  }

  const std::string& error() const override { return error_; }
  bool datagrams() const override { return false; }
  int fd() const override { return fd_.get(); }

 private:
  UniqueFd fd_;
  std::string name_;
  StreamWords words_;
  std::vector<uint8_t> scratch_;
  std::string error_;
};

}  // namespace

std::unique_ptr<ByteSource> make_stream_source(UniqueFd fd, std::string name, StreamWords words) {
  return std::make_unique<StreamSource>(std::move(fd), std::move(name), words);
}

}  // namespace brickyard::drivers
