#include "ouster_crc64.hpp"

#include <array>

namespace brickyard::drivers {

namespace {

constexpr uint64_t kReflectedPolynomial = 0xC96C5795D7870F42ull;  // ECMA-182's, bit-reversed

// Byte-at-a-time table: entry i is the register after shifting the 8 bits of i through it.
constexpr std::array<uint64_t, 256> make_table() {
  std::array<uint64_t, 256> table{};
  for (uint64_t i = 0; i < 256; ++i) {
    uint64_t r = i;
    for (int bit = 0; bit < 8; ++bit) r = (r & 1u) ? (r >> 1) ^ kReflectedPolynomial : r >> 1;
    table[i] = r;
  }
  return table;
}

constexpr std::array<uint64_t, 256> kTable = make_table();

}  // namespace

uint64_t crc64_xz(const uint8_t* data, size_t size) {
  uint64_t crc = ~0ull;
  for (size_t i = 0; i < size; ++i) crc = kTable[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

}  // namespace brickyard::drivers
