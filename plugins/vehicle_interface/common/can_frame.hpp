#pragma once
// One CAN frame as the vehicle interface's readers and writers pass it around, framework-free:
// classic CAN 2.0 (0..8 bytes, or a remote request) and CAN FD (up to 64 bytes). The identifier
// is kept without the flag bits Linux packs into can_id (linux/can.h: CAN_EFF_FLAG, CAN_RTR_FLAG,
// CAN_ERR_FLAG); the flags are fields. docs/can-dbc.md.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace brickyard::vehicle_interface {

inline constexpr uint32_t kStandardIdMax = 0x7FF;       // 11 bits
inline constexpr uint32_t kExtendedIdMax = 0x1FFFFFFF;  // 29 bits
inline constexpr size_t kClassicMaxBytes = 8;
inline constexpr size_t kFdMaxBytes = 64;
// linux/can.h's canfd_frame.flags, carried as they are by candump logs and cannelloni.
inline constexpr uint8_t kFdBitRateSwitch = 0x01;  // CANFD_BRS
inline constexpr uint8_t kFdErrorStateIndicator = 0x02;  // CANFD_ESI

struct CanFrame {
  uint32_t id = 0;  // 11 bits, or 29 when extended
  bool extended = false;
  bool remote = false;  // remote transmission request: no data; `length` is the length asked for
  bool fd = false;      // CAN FD: no remote frames, lengths up to 64 (kFdLengths)
  uint8_t fd_flags = 0;
  uint8_t length = 0;   // payload bytes
  std::array<uint8_t, kFdMaxBytes> data{};  // bytes past `length` stay 0, so frames compare by value

  bool operator==(const CanFrame&) const = default;
};

// CAN FD carries 0..8, 12, 16, 20, 24, 32, 48 or 64 bytes (the DLC codes 9..15 name the last seven).
bool is_fd_length(size_t bytes);

// Why a frame cannot go on a bus as it is (an id too wide for its format, a length its format
// cannot carry, a remote FD frame, flags on a classic frame, bytes set past its length), or "" when it can.
std::string frame_problem(const CanFrame& frame);

}  // namespace brickyard::vehicle_interface
