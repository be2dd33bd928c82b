#pragma once
// OEM7 binary framing and the four logs' body layouts (little-endian, packed, offsets as the OEM7
// reference's field tables give them), read from and written to bytes. Framing, CRC checks and
// refusals are novatel_oem7.hpp's; here a frame is already known to be whole.
#include "oem7_messages.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace brickyard::drivers {

inline constexpr uint8_t kOem7Sync0 = 0xAA, kOem7Sync1 = 0x44;
inline constexpr uint8_t kOem7SyncLong = 0x12, kOem7SyncShort = 0x13;  // third sync byte
inline constexpr size_t kOem7HeaderBytes = 28;       // the OEM7 long header; its own byte 3 says so
inline constexpr size_t kOem7ShortHeaderBytes = 12;  // "Short Binary Message Header Structure"
inline constexpr size_t kOem7CrcBytes = 4;

// Documented body sizes (a longer body, from a newer firmware appending fields, is read up to these).
inline constexpr size_t kBestPosBodyBytes = 72;
inline constexpr size_t kBestVelBodyBytes = 44;
inline constexpr size_t kInsPvaXBodyBytes = 126;
inline constexpr size_t kRawImuSXBodyBytes = 40;

// The header of a frame at least kOem7HeaderBytes (kOem7ShortHeaderBytes) long.
Oem7Header read_binary_header(const uint8_t* frame);
Oem7Header read_binary_short_header(const uint8_t* frame);

// The body into `out` (its header untouched); false when the body is shorter than documented.
bool read_body(std::span<const uint8_t> body, BestPos& out);
bool read_body(std::span<const uint8_t> body, BestVel& out);
bool read_body(std::span<const uint8_t> body, InsPvaX& out);
bool read_body(std::span<const uint8_t> body, RawImuSX& out);

// Appending a header (message type 0: binary, original) or a body to `bytes`.
void write_binary_header(const Oem7Header& header, uint16_t message_id, uint16_t body_bytes, std::vector<uint8_t>& bytes);
void write_binary_short_header(const Oem7Header& header, uint16_t message_id, uint8_t body_bytes, std::vector<uint8_t>& bytes);
void write_body(const BestPos& m, std::vector<uint8_t>& bytes);
void write_body(const BestVel& m, std::vector<uint8_t>& bytes);
void write_body(const InsPvaX& m, std::vector<uint8_t>& bytes);
void write_body(const RawImuSX& m, std::vector<uint8_t>& bytes);

}  // namespace brickyard::drivers
