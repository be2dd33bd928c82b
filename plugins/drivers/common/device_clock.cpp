#include "device_clock.hpp"

#include <cmath>

namespace brickyard::drivers {

int64_t DeviceClock::stamp_ns(double device_s, int64_t receive_ns) {
  const double receive_s = static_cast<double>(receive_ns) * 1e-9;
  const double offset = receive_s - device_s;
  if (!offsets_.empty() && std::abs(offset - offsets_.front().second) > p_.max_jump_s) {
    offsets_.clear();
    ++restarts_;
  }
  while (!offsets_.empty() && offsets_.back().second >= offset) offsets_.pop_back();
  offsets_.emplace_back(receive_s, offset);
  while (offsets_.front().first < receive_s - p_.window_s) offsets_.pop_front();
  last_delay_s_ = offset - offsets_.front().second;
  // The delay is computed in seconds and taken off the receive time in nanoseconds: the offset
  // itself (GPS time is 1.4e9 s) would lose a tenth of a microsecond in a double's round trip.
  return receive_ns - static_cast<int64_t>(std::llround(last_delay_s_ * 1e9));
}

}  // namespace brickyard::drivers
