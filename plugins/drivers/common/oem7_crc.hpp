#pragma once
// NovAtel's 32-bit CRC of OEM7 ASCII and binary logs, as the OEM7 reference documents it: the
// reflected polynomial 0xEDB88320, register starting at 0, no final inversion (so it is not the
// zlib CRC-32, which starts at and ends with 0xFFFFFFFF). Binary logs: over the header and body;
// ASCII logs: over every byte between the '#' (or '%') and the '*'.
#include <cstddef>
#include <cstdint>

namespace brickyard::drivers {

// The CRC of `size` bytes, continuing from `crc` (0 to start).
uint32_t oem7_crc32(const uint8_t* data, size_t size, uint32_t crc = 0);

}  // namespace brickyard::drivers
