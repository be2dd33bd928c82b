#pragma once
// Framework-free: how long a driver took from a message's last bytes reaching the host (the
// kernel's receive time of the datagram that completed it: ByteSource::arrivals_ns) to the message
// handed to its output port, on the real clock: the driver's own added latency, the wire's and the
// device's excluded (the time rule's stamp delay is device_clock.hpp's). Taken before the port's
// publish, not after: in it the readers' queues are filled and their nodes woken, and on a busy
// host a woken reader (the ground filter, whose frame the cloud completes) takes the publishing
// thread's core before the call returns: its own computing time, not the message's delay (measured
// after, one LiDAR's p99 read 2.3 ms where its poll and decode took 1.0). Kept as a histogram whose bins
// grow by 1 % from 1 µs to 1000 s (its memory bounded on a long run, each quantile given at most
// 1 % high; the largest kept exactly). The plugins report it as wire_to_message_s_p50, _p99 and
// _max (driver_metrics.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace brickyard::drivers {

class LatencySpread {
 public:
  static constexpr double kFirst_s = 1e-6, kGrowth = 1.01;
  static constexpr std::size_t kBins = 2084;  // 1e-6 * 1.01^2083 > 1000 s

  // A message published at `published_ns` whose last bytes arrived at `arrival_ns` (< 0: not known).
  void add(std::int64_t published_ns, std::int64_t arrival_ns) {
    if (arrival_ns < 0) return;
    const double s = std::max(0.0, static_cast<double>(published_ns - arrival_ns) * 1e-9);
    ++bins_[bin_of(s)];
    max_s_ = std::max(max_s_, s);
    ++count_;
  }

  std::uint64_t count() const { return count_; }
  // The upper edge of the bin holding the q-th quantile (at most the largest): never under it.
  double quantile_s(double q) const {
    const auto want = static_cast<std::uint64_t>(q * static_cast<double>(count_ - 1)) + 1;
    std::uint64_t seen = 0;
    for (std::size_t b = 0; b < kBins; ++b)
      if ((seen += bins_[b]) >= want) return std::min(max_s_, kFirst_s * std::pow(kGrowth, static_cast<double>(b)));
    return max_s_;
  }

  double max_s() const { return max_s_; }


 private:
  std::array<std::uint32_t, kBins> bins_{};
  // Bin b holds (kFirst_s kGrowth^(b-1), kFirst_s kGrowth^b]; bin 0 everything up to kFirst_s.
  static std::size_t bin_of(double s) {
    if (s <= kFirst_s) return 0;
    const double b = std::ceil(std::log(s / kFirst_s) / std::log(kGrowth));
    return std::min(kBins - 1, static_cast<std::size_t>(b));
  }

  double max_s_ = 0;
  std::uint64_t count_ = 0;
};

}  // namespace brickyard::drivers
