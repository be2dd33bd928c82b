#include "can_frame.hpp"

namespace brickyard::vehicle_interface {

bool is_fd_length(size_t bytes) {
  if (bytes <= 8) return true;
  switch (bytes) {
    case 12: case 16: case 20: case 24: case 32: case 48: case 64: return true;
    default: return false;
  }
}

std::string frame_problem(const CanFrame& frame) {
  const uint32_t id_max = frame.extended ? kExtendedIdMax : kStandardIdMax;
  if (frame.id > id_max) return frame.extended ? "id wider than 29 bits" : "id wider than 11 bits";
  if (frame.fd) {
    if (frame.remote) return "CAN FD has no remote frames";
    if (!is_fd_length(frame.length)) return "length " + std::to_string(frame.length) + " is not a CAN FD length";
  } else {
    if (frame.length > kClassicMaxBytes) return "length " + std::to_string(frame.length) + " over 8 bytes";
    if (frame.fd_flags != 0) return "CAN FD flags on a classic frame";
  }
  const size_t used = frame.remote ? 0 : frame.length;
  for (size_t i = used; i < frame.data.size(); ++i)
    if (frame.data[i] != 0) return "bytes set past the frame's length";
  return "";
}

}  // namespace brickyard::vehicle_interface
