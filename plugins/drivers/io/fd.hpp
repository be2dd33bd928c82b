#pragma once
// What every transport shares: a file descriptor closed by its owner's destructor (no transport
// leaks one, whatever path it leaves by), and device errors worded one way ("NAME: WHAT: OS error").
#include "byte_source.hpp"

#include <string>
#include <string_view>
#include <utility>

namespace brickyard::drivers {

class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    reset(std::exchange(other.fd_, -1));
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd() { reset(); }

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  void reset(int fd = -1);
  int release() { return std::exchange(fd_, -1); }  // handed on, not closed

 private:
  int fd_ = -1;
};

// The OS's words for an errno value, thread-safe (strerror's buffer is not).
std::string os_error(int err);
// "NAME: WHAT: OS error" ("serial:///dev/ttyUSB9: cannot open: No such file or directory").
std::string device_error(std::string_view device, std::string_view what, int err);
// The spec as the user wrote it, or, for a spec built in code, its kind and address.
std::string device_name(const SourceSpec& spec);

}  // namespace brickyard::drivers
