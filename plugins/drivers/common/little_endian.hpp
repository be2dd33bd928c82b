#pragma once
// Little-endian fields read from and written to bytes, whatever the host's byte order: the Ouster
// packets' (lidar and IMU) and their encoder's. Framework-free.
#include <cstdint>
#include <cstring>

namespace brickyard::drivers::le {

inline std::uint16_t u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }
inline std::uint32_t u32(const std::uint8_t* p) { return u16(p) | static_cast<std::uint32_t>(u16(p + 2)) << 16; }
inline std::uint64_t u64(const std::uint8_t* p) { return u32(p) | static_cast<std::uint64_t>(u32(p + 4)) << 32; }
// The n low bytes of a field (n <= 8).
inline std::uint64_t bytes(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}
inline float f32(const std::uint8_t* p) {
  const std::uint32_t bits = u32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

inline void put_bytes(std::uint8_t* p, std::uint64_t v, int n) {
  for (int i = 0; i < n; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline void put16(std::uint8_t* p, std::uint32_t v) { put_bytes(p, v, 2); }
inline void put32(std::uint8_t* p, std::uint32_t v) { put_bytes(p, v, 4); }
inline void put64(std::uint8_t* p, std::uint64_t v) { put_bytes(p, v, 8); }
inline void put_f32(std::uint8_t* p, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put32(p, bits);
}

}  // namespace brickyard::drivers::le
