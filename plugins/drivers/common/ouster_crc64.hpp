#pragma once
// The 64-bit CRC that Ouster firmware 3.x appends to each lidar packet, in the last 8 bytes of the
// packet footer, little-endian, over every byte before it. No public Ouster document we could read
// names the polynomial; it was identified on the vendor's own capture (data/lidar_packets/
// crc_test.pcap, firmware v3.2): all 34 lidar packets match CRC-64/XZ and none of the other
// catalogued CRC-64s (ECMA-182, GO-ISO, WE, REDIS, MS, NVME). CRC-64/XZ is the ECMA-182 polynomial
// 0x42F0E1EBA9EA3693, reflected (0xC96C5795D7870F42), register starting at all ones, result
// inverted; its check value over "123456789" is 0x995DC9BBDF1939FA (docs/drivers-formats.md).
#include <cstddef>
#include <cstdint>

namespace brickyard::drivers {

uint64_t crc64_xz(const uint8_t* data, size_t size);

}  // namespace brickyard::drivers
