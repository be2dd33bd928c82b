#pragma once
// A recording replayed at its own pace, framework-free: a record made `t` seconds after the first
// is due once the run's clock is t / rate past the moment the first was due (rate 2: twice as
// fast; rate 0: every record at once). The recorded times are the device's (GPS time of an OEM7
// log, a pcap record's capture time); the run's clock is the caller's (sim or real).
#include <cstdint>
#include <optional>

namespace brickyard::drivers {

class ReplayPacer {
 public:
  explicit ReplayPacer(double rate) : rate_(rate) {}

  bool due(double recorded_s, int64_t now_ns) {
    if (!first_) first_ = recorded_s, start_ns_ = now_ns;
    if (rate_ <= 0) return true;
    return static_cast<double>(now_ns - start_ns_) * 1e-9 * rate_ >= recorded_s - *first_;
  }

 private:
  double rate_;
  std::optional<double> first_;
  int64_t start_ns_ = 0;
};

}  // namespace brickyard::drivers
