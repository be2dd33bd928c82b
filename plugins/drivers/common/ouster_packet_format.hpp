#pragma once
// The byte layout of an Ouster lidar packet per udp_profile_lidar (firmware 2.x and 3.x), and the
// readers of its parts: the packet header, each column's header, each pixel's fields. Words are
// little-endian. LEGACY packets are columns only (16-byte header, 12-byte pixels, a 4-byte status
// word); the other profiles have a 32-byte packet header, 12-byte column headers, the profile's
// pixels, and a 32-byte footer whose last 8 bytes carry a CRC-64 from firmware 3.1 on. The
// callers check a packet's size against packet_bytes() before reading any part of it.
// Sources and the bit positions: docs/drivers-formats.md, "Ouster LiDAR packets".
#include "ouster_frame.hpp"
#include "ouster_metadata.hpp"

#include <cstddef>
#include <cstdint>

namespace brickyard::drivers {

struct OusterPacketLayout {
  OusterProfile profile = OusterProfile::legacy;
  int columns_per_packet = 16;
  int pixels_per_column = 0;
  size_t header_bytes = 0;         // packet header: 0 (LEGACY) or 32
  size_t column_header_bytes = 0;  // 16 (LEGACY) or 12
  size_t pixel_bytes = 0;          // 12 (LEGACY, single return), 4 (low data rate), 16 (dual)
  size_t column_status_bytes = 0;  // after the pixels: 4 (LEGACY) or 0
  size_t footer_bytes = 0;         // 0 (LEGACY) or 32

  size_t column_bytes() const { return column_header_bytes + pixel_bytes * pixels_per_column + column_status_bytes; }
  size_t packet_bytes() const { return header_bytes + column_bytes() * columns_per_packet + footer_bytes; }
};

OusterPacketLayout ouster_packet_layout(const OusterMetadata& metadata);

struct OusterColumnHeader {
  uint64_t timestamp_ns = 0;
  uint16_t measurement_id = 0;
  uint16_t frame_id = 0;       // LEGACY only (the others carry it in the packet header)
  uint32_t encoder_count = 0;  // LEGACY only
  uint32_t status = 0;
  bool valid = false;
};

// `packet` holds at least header_bytes (non-LEGACY layouts only).
OusterPacketHeader read_ouster_packet_header(const uint8_t* packet);
// `column` points at a column's first byte; the column holds layout.column_bytes().
OusterColumnHeader read_ouster_column_header(const OusterPacketLayout& layout, const uint8_t* column);
// Whether the packet's last 8 bytes are the CRC-64 of the bytes before them.
bool ouster_packet_crc_ok(const uint8_t* packet, size_t size);

// Sizes the frame's arrays for this sensor and profile and clears its per-column fields; pixels
// keep what a recycled frame held until finish_ouster_frame() (its columns marked stale).
void reset_ouster_frame(OusterFrame& frame, const OusterMetadata& metadata, uint16_t frame_id);
// Zeroes the pixels of every column that did not arrive, before the frame is handed out.
void finish_ouster_frame(OusterFrame& frame);
// Copies the pixels of one column (its first pixel at `pixels`) into column `column` of `frame`.
void read_ouster_pixels(const OusterPacketLayout& layout, const uint8_t* pixels, int column, OusterFrame& frame);

}  // namespace brickyard::drivers
