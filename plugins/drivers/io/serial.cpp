// serial://PATH: a tty opened without becoming the process's controlling terminal, put in raw
// mode at the spec's rate and framing, and read (source) or written (sink) without blocking.
#include "serial_settings.hpp"
#include "transports.hpp"

#include <fcntl.h>

#include <cerrno>

namespace brickyard::drivers {
namespace {

UniqueFd open_tty(const SourceSpec& spec, const std::string& name, std::string& error) {
  UniqueFd fd(::open(spec.path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
  if (!fd.valid()) {
    error = device_error(name, "cannot open", errno);
    return fd;
  }
  if (std::string failed = configure_serial(fd.get(), spec.baud, spec.framing); !failed.empty()) {
    error = name + ": " + failed;
    fd.reset();
  }
  return fd;
}

}  // namespace

std::unique_ptr<ByteSource> open_serial_source(const SourceSpec& spec, const std::string& name, std::string& error) {
  UniqueFd fd = open_tty(spec, name, error);
  if (!fd.valid()) return nullptr;
  return make_stream_source(std::move(fd), name, {"the line hung up (unplugged?)", "read failed"});
}

std::unique_ptr<ByteSink> open_serial_sink(const SourceSpec& spec, const std::string& name, std::string& error) {
  UniqueFd fd = open_tty(spec, name, error);
  if (!fd.valid()) return nullptr;
  return make_fd_sink(std::move(fd), name);
}

}  // namespace brickyard::drivers
