#pragma once
// Plugin-side (SDK): a sensor that falls silent, reported once a silence, and the progress line's
// status ("silent", then "heard" when it speaks again). Silent: nothing heard for `after_s` since
// the last message (or since the first look). Not a silence: a recording that has ended
// (`expected` false).
#include <brickyard/context.hpp>

#include <cstdint>
#include <string>

namespace brickyard::drivers {

class SilenceWatch {
 public:
  SilenceWatch() = default;
  SilenceWatch(std::string sensor, double after_s) : sensor_(std::move(sensor)), after_ns_(static_cast<int64_t>(after_s * 1e9)) {}

  void heard(int64_t now_ns) {
    last_ns_ = now_ns;
    silent_ = false;
  }

  void check(Context& ctx, int64_t now_ns, bool expected = true) {
    if (last_ns_ < 0) last_ns_ = now_ns;
    if (shown_silent_ && !silent_) ctx.status(sensor_, "heard"), shown_silent_ = false;
    if (silent_ || !expected || now_ns - last_ns_ < after_ns_) return;
    silent_ = true;
    ++silences_;
    ctx.log(LogLevel::warn, sensor_ + " silent: nothing for " + std::to_string((now_ns - last_ns_) / 1000000) + " ms");
    ctx.status(sensor_, "silent");
    shown_silent_ = true;
  }

  uint64_t silences() const { return silences_; }

 private:
  std::string sensor_;
  int64_t after_ns_ = 0, last_ns_ = -1;
  bool silent_ = false, shown_silent_ = false;
  uint64_t silences_ = 0;
};

}  // namespace brickyard::drivers
