#pragma once
// Test support: a CAN frame from its identifier and its bytes, as the tests write frames by hand.
#include "vehicle_interface/common/can_frame.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace brickyard::vehicle_interface {

inline CanFrame frame_of(uint32_t id, const std::vector<uint8_t>& bytes, bool extended = false) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.length = static_cast<uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), f.data.begin());  // no memcpy: an empty vector's data() may be null
  return f;
}

}  // namespace brickyard::vehicle_interface
