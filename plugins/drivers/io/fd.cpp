#include "fd.hpp"

#include <unistd.h>

#include <system_error>

namespace brickyard::drivers {

void UniqueFd::reset(int fd) {
  // close() is not retried on EINTR: Linux frees the descriptor whatever close returns, and a
  // retry could close one another thread has just been given.
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
}

std::string os_error(int err) { return std::error_code(err, std::generic_category()).message(); }

std::string device_error(std::string_view device, std::string_view what, int err) {
  std::string message(device);
  message += ": ";
  message += what;
  if (err != 0) {
    message += ": ";
    message += os_error(err);
  }
  return message;
}

std::string device_name(const SourceSpec& spec) {
  if (!spec.text.empty()) return spec.text;
  switch (spec.kind) {
    case SourceSpec::Kind::udp: return "udp://" + spec.host + ":" + std::to_string(spec.port);
    case SourceSpec::Kind::tcp: return "tcp://" + spec.host + ":" + std::to_string(spec.port);
    case SourceSpec::Kind::serial: return "serial://" + spec.path;
    case SourceSpec::Kind::file: return "file://" + spec.path;
    case SourceSpec::Kind::pcap: return "pcap://" + spec.path;
  }
  return "device";
}

}  // namespace brickyard::drivers
