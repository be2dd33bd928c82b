#include "device_clock.hpp"

#include <cmath>
#include <cstdlib>

namespace brickyard::drivers {

int64_t DeviceClock::stamp_ns(int64_t device_ns, int64_t receive_ns) {
  const int64_t offset = receive_ns - device_ns;
  const int64_t max_jump = std::llround(p_.max_jump_s * 1e9), window = std::llround(p_.window_s * 1e9);
  if (!offsets_.empty() && std::llabs(offset - offsets_.front().second) > max_jump) {
    offsets_.clear();
    ++restarts_;
  }
  while (!offsets_.empty() && offsets_.back().second >= offset) offsets_.pop_back();
  offsets_.emplace_back(receive_ns, offset);
  while (offsets_.front().first < receive_ns - window) offsets_.pop_front();
  last_delay_ns_ = offset - offsets_.front().second;
  return receive_ns - last_delay_ns_;
}

}  // namespace brickyard::drivers
