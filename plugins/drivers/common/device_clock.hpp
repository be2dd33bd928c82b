#pragma once
// A device's time to the run's clock, framework-free. A message is stamped when the device
// measured it, in the run's clock: stamp = device time + offset, the offset the least of (receive
// time - device time) over the last `window_s` of receive time. Why the least: a message is never
// received before it is measured, and the transport only delays (a serial line's bytes, a busy
// host); the message delayed least is the best witness of the offset, and its error is that
// message's own delay (measured: docs/drivers-formats.md, "Time"). A stamp is so never later than
// its receive time. Device time that jumps against the run's clock by more than `max_jump_s` (a
// receiver reset, NMEA's midnight) starts the estimate again from that message.
#include <cstdint>
#include <deque>
#include <utility>

namespace brickyard::drivers {

struct DeviceClockParams {
  double window_s = 10;   // how far back the least delay is looked for
  double max_jump_s = 1;  // a step in (receive - device) larger than this restarts the estimate
};

class DeviceClock {
 public:
  explicit DeviceClock(DeviceClockParams p = {}) : p_(p) {}

  // The run-clock stamp of a message measured at `device_ns` (the device's clock) and received at
  // `receive_ns` (the run's). Integers throughout: a stamp lands on its instant to the nanosecond.
  int64_t stamp_ns(int64_t device_ns, int64_t receive_ns);
  // Of the last message: how long before its receipt it is stamped, s (the delay it is credited).
  double last_delay_s() const { return static_cast<double>(last_delay_ns_) * 1e-9; }
  uint64_t restarts() const { return restarts_; }

 private:
  DeviceClockParams p_;
  // (receive time, receive - device), ns, offsets increasing from front to back: the front is the
  // least within the window (a monotonic queue: each message enters and leaves it once).
  std::deque<std::pair<int64_t, int64_t>> offsets_;
  int64_t last_delay_ns_ = 0;
  uint64_t restarts_ = 0;
};

}  // namespace brickyard::drivers
