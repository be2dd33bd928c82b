#include "exec/node_runtime.hpp"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>

namespace brickyard::fw {

NodeRuntime::~NodeRuntime() {
  if (wake_event_fd >= 0) ::close(wake_event_fd);
}

void NodeRuntime::wake_device_wait() const {
  if (wake_event_fd < 0) return;
  const std::uint64_t one = 1;
  // The counter only grows: a full one (never, in practice) still leaves the descriptor readable.
  [[maybe_unused]] const ssize_t n = ::write(wake_event_fd, &one, sizeof one);
}

}  // namespace brickyard::fw
