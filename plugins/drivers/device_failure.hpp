#pragma once
// Plugin-side (SDK): a driver's live device that failed (closed by its peer, unplugged) said once
// in the log, and the node no longer woken by it (its descriptor is gone: Context::wake_on_readable).
#include <brickyard/context.hpp>

#include <string>

namespace brickyard::drivers {

class DeviceFailure {
 public:
  // `error`: the source's device error, empty while it works; `lost`: what no longer comes ("fixes").
  void check(Context& ctx, const std::string& error, const char* lost) {
    if (error.empty() || said_) return;
    said_ = true;
    ctx.log(LogLevel::error, "source " + error + ": no more " + lost + " from it");
    ctx.wake_on_readable(-1);
  }

 private:
  bool said_ = false;
};

}  // namespace brickyard::drivers
