#pragma once
// Plugin-side (SDK): a driver's live device that failed (closed by its peer, unplugged) said once
// in the log, the node no longer woken by it (its descriptor is gone: Context::wake_on_readable),
// and, when the device is opened again (reopening_device.hpp), said again and waited on anew.
#include <brickyard/context.hpp>

#include <string>

namespace brickyard::drivers {

class DeviceFailure {
 public:
  // The node woken by the device's descriptor (-1: none), at configure; `reopens`: whether the
  // device is opened again after a failure.
  void watch(Context& ctx, int fd, bool reopens) {
    reopens_ = reopens;
    ctx.wake_on_readable(fd_ = fd);
  }

  // `error`: the device's failure, empty while it is open; `fd`: its descriptor now; `lost`: what
  // does not come meanwhile ("fixes").
  void check(Context& ctx, const std::string& error, int fd, const char* lost) {
    if (!error.empty()) {
      if (!failed_) ctx.log(LogLevel::error, "source " + error + ": no more " + lost + " from it" + (reopens_ ? " until it opens again" : ""));
      failed_ = true;
      fd = -1;
    } else if (failed_) {
      ctx.log(LogLevel::info, "source open again: " + std::string(lost) + " from it again");
      failed_ = false;
    }
    if (fd != fd_) ctx.wake_on_readable(fd_ = fd);
  }

 private:
  int fd_ = -1;
  bool reopens_ = false, failed_ = false;
};

}  // namespace brickyard::drivers
