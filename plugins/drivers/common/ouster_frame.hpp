#pragma once
// One rotation of an Ouster sensor as its packets carried it, framework-free: per column the
// header fields, per pixel the profile's fields, in the sensor's staggered order (row r of column
// c is what beam r measured in the column whose measurement id is c, at index r * width + c). A
// field the profile does not carry stays empty. ouster_xyz.hpp turns a frame into points.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace brickyard::drivers {

// From the packet header (not in LEGACY packets, which have none).
struct OusterPacketHeader {
  uint16_t packet_type = 0;  // 1: lidar
  uint16_t frame_id = 0;
  uint32_t initialization_id = 0;  // 24 bits
  uint64_t serial_number = 0;      // 40 bits
  uint8_t alert_flags = 0;
  uint8_t countdown_thermal_shutdown = 0;  // seconds
  uint8_t countdown_shot_limiting = 0;     // seconds
  uint8_t thermal_shutdown = 0;            // 0 normal, 1 imminent
  uint8_t shot_limiting = 0;               // 0 normal, 1 imminent, 2..9 reducing
};

struct OusterFrame {
  uint16_t frame_id = 0;
  int width = 0;   // columns per frame
  int height = 0;  // pixels per column
  OusterPacketHeader last_header;  // of the frame's last packet (thermal and shot-limiting status)

  // Per column, indexed by measurement id.
  std::vector<uint64_t> timestamp_ns;   // the column's measurement time, sensor clock
  std::vector<uint32_t> encoder_count;  // LEGACY only; 0 in the other profiles
  std::vector<uint32_t> status;         // LEGACY: 0xFFFFFFFF valid; others: bit 0 valid
  std::vector<uint8_t> received;        // 1: the column arrived, valid
  // 1: the column's pixels may hold the values of the frame this buffer held before (recycled);
  // finish_ouster_frame zeroes those that did not arrive again. A windowed sensor fires the same
  // columns every rotation: nothing to zero, where zeroing every unfired column was 0.9 MB a frame.
  std::vector<uint8_t> stale;

  // Per pixel, index row * width + column. Ranges in millimetres (RNG15 already scaled by 8).
  std::vector<uint32_t> range_mm, range2_mm;
  std::vector<uint16_t> signal, signal2, near_ir;
  std::vector<uint8_t> reflectivity, reflectivity2, flags, flags2;

  int columns_expected = 0;  // in the column window
  int columns_received = 0;  // valid and in the window
  bool complete() const { return columns_expected > 0 && columns_received == columns_expected; }
  size_t pixel(int row, int column) const { return static_cast<size_t>(row) * width + column; }
};

}  // namespace brickyard::drivers
