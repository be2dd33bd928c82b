#include "ouster_packet_format.hpp"

#include "little_endian.hpp"
#include "ouster_crc64.hpp"

#include <algorithm>
#include <utility>

namespace brickyard::drivers {

namespace {

constexpr uint32_t kRange19 = (1u << 19) - 1;
constexpr uint32_t kRange20 = (1u << 20) - 1;
constexpr uint32_t kRange15 = (1u << 15) - 1;
constexpr uint32_t kLowDataRateRangeUnitMm = 8;

// Each reader walks one column's pixels (row r at pixels + r * pixel_bytes) into the frame's
// arrays at row * width + column. Bit positions: docs/drivers-formats.md.
void read_legacy(const uint8_t* p, int rows, size_t at, size_t stride, OusterFrame& f) {
  for (int r = 0; r < rows; ++r, p += 12, at += stride) {
    uint32_t word = le::u32(p);
    f.range_mm[at] = word & kRange20;
    f.flags[at] = static_cast<uint8_t>(word >> 28);
    f.reflectivity[at] = p[4];  // a 16-bit field of which firmware 2.1+ fills the low 8 bits
    f.signal[at] = le::u16(p + 6);
    f.near_ir[at] = le::u16(p + 8);
  }
}

void read_single_return(const uint8_t* p, int rows, size_t at, size_t stride, OusterFrame& f) {
  for (int r = 0; r < rows; ++r, p += 12, at += stride) {
    uint32_t word = le::u32(p);
    f.range_mm[at] = word & kRange19;
    f.flags[at] = static_cast<uint8_t>((word >> 19) & 0x1Fu);
    f.reflectivity[at] = p[4];
    f.signal[at] = le::u16(p + 6);
    f.near_ir[at] = le::u16(p + 8);
  }
}

void read_low_data_rate(const uint8_t* p, int rows, size_t at, size_t stride, OusterFrame& f) {
  for (int r = 0; r < rows; ++r, p += 4, at += stride) {
    uint16_t word = le::u16(p);
    f.range_mm[at] = (word & kRange15) * kLowDataRateRangeUnitMm;
    f.flags[at] = static_cast<uint8_t>(word >> 15);
    f.reflectivity[at] = p[2];
    f.near_ir[at] = p[3];
  }
}

void read_dual_return(const uint8_t* p, int rows, size_t at, size_t stride, OusterFrame& f) {
  for (int r = 0; r < rows; ++r, p += 16, at += stride) {
    uint32_t first = le::u32(p);
    uint32_t second = le::u32(p + 4);
    f.range_mm[at] = first & kRange19;
    f.flags[at] = static_cast<uint8_t>((first >> 19) & 0x1Fu);
    f.reflectivity[at] = static_cast<uint8_t>(first >> 24);
    f.range2_mm[at] = second & kRange19;
    f.flags2[at] = static_cast<uint8_t>((second >> 19) & 0x1Fu);
    f.reflectivity2[at] = static_cast<uint8_t>(second >> 24);
    f.signal[at] = le::u16(p + 8);
    f.signal2[at] = le::u16(p + 10);
    f.near_ir[at] = le::u16(p + 12);
  }
}

// Sized, not cleared: a recycled frame keeps its old pixels until finish_ouster_frame() zeroes the
// stale columns that did not arrive, so a whole frame is written once, not twice. A buffer of
// another size is cleared: only its own last frame's columns are known.
template <typename T>
bool sized(std::vector<T>& v, size_t n, bool present) {
  const size_t want = present ? n : 0;
  if (v.size() == want) return true;
  v.assign(want, T{});
  return false;
}

// Zeroes the columns [first, last) of each run in every row: the image is row by row, so a run
// of columns is contiguous in each row (column by column, every pixel written is another cache line:
// a 127-degree window's frame left 663 of 1024 columns to zero, 2 ms a frame).
template <typename T>
void zero_columns(std::vector<T>& v, const std::vector<std::pair<size_t, size_t>>& runs, size_t width) {
  for (size_t row = 0; row + width <= v.size(); row += width)
    for (const auto& [first, last] : runs) std::fill(v.begin() + static_cast<std::ptrdiff_t>(row + first), v.begin() + static_cast<std::ptrdiff_t>(row + last), T{});
}

}  // namespace

OusterPacketLayout ouster_packet_layout(const OusterMetadata& m) {
  OusterPacketLayout l;
  l.profile = m.profile;
  l.columns_per_packet = m.columns_per_packet;
  l.pixels_per_column = m.pixels_per_column;
  bool legacy = m.profile == OusterProfile::legacy;
  l.header_bytes = legacy ? 0 : 32;
  l.column_header_bytes = legacy ? 16 : 12;
  l.column_status_bytes = legacy ? 4 : 0;
  l.footer_bytes = legacy ? 0 : 32;
  switch (m.profile) {
    case OusterProfile::legacy:
    case OusterProfile::single_return: l.pixel_bytes = 12; break;
    case OusterProfile::low_data_rate: l.pixel_bytes = 4; break;
    case OusterProfile::dual_return: l.pixel_bytes = 16; break;
  }
  return l;
}

OusterPacketHeader read_ouster_packet_header(const uint8_t* p) {
  OusterPacketHeader h;
  h.packet_type = le::u16(p);
  h.frame_id = le::u16(p + 2);
  h.initialization_id = static_cast<uint32_t>(le::bytes(p + 4, 3));
  h.serial_number = le::bytes(p + 7, 5);
  h.alert_flags = p[12];
  h.countdown_thermal_shutdown = p[16];
  h.countdown_shot_limiting = p[17];
  h.thermal_shutdown = p[18];
  h.shot_limiting = p[19];
  return h;
}

OusterColumnHeader read_ouster_column_header(const OusterPacketLayout& layout, const uint8_t* c) {
  OusterColumnHeader h;
  h.timestamp_ns = le::u64(c);
  h.measurement_id = le::u16(c + 8);
  if (layout.profile == OusterProfile::legacy) {
    h.frame_id = le::u16(c + 10);
    h.encoder_count = le::u32(c + 12);
    h.status = le::u32(c + layout.column_bytes() - 4);
    h.valid = h.status == 0xFFFFFFFFu;
  } else {
    h.status = le::u16(c + 10);
    h.valid = (h.status & 1u) != 0;
  }
  return h;
}

bool ouster_packet_crc_ok(const uint8_t* packet, size_t size) {
  return size >= 8 && crc64_xz(packet, size - 8) == le::u64(packet + size - 8);
}

void reset_ouster_frame(OusterFrame& f, const OusterMetadata& m, uint16_t frame_id) {
  f.frame_id = frame_id;
  f.width = m.columns_per_frame;
  f.height = m.pixels_per_column;
  f.last_header = {};
  f.columns_expected = m.columns_in_window();
  f.columns_received = 0;
  const size_t w = static_cast<size_t>(f.width);
  f.timestamp_ns.assign(w, 0);
  f.encoder_count.assign(w, 0);
  f.status.assign(w, 0);
  const size_t n = w * static_cast<size_t>(f.height);
  const bool dual = m.profile == OusterProfile::dual_return;
  bool kept = sized(f.range_mm, n, true);
  kept &= sized(f.reflectivity, n, true);
  kept &= sized(f.flags, n, true);
  kept &= sized(f.near_ir, n, true);
  kept &= sized(f.signal, n, m.profile != OusterProfile::low_data_rate);
  kept &= sized(f.range2_mm, n, dual);
  kept &= sized(f.reflectivity2, n, dual);
  kept &= sized(f.flags2, n, dual);
  kept &= sized(f.signal2, n, dual);
  // After finish_ouster_frame only the columns that arrived hold values: those of the last frame.
  if (kept && f.received.size() == w) f.stale.swap(f.received);
  else f.stale.assign(w, 0);
  f.received.assign(w, 0);
}

void finish_ouster_frame(OusterFrame& f) {
  const size_t w = static_cast<size_t>(f.width);
  auto left_over = [&](size_t c) { return c < f.stale.size() && f.stale[c] && !f.received[c]; };
  std::vector<std::pair<size_t, size_t>> runs;  // the stale columns not received, as runs [first, last)
  for (size_t c = 0; c < w;) {
    if (!left_over(c)) { ++c; continue; }
    const size_t first = c;
    while (c < w && left_over(c)) ++c;
    runs.emplace_back(first, c);
  }
  if (runs.empty()) return;
  zero_columns(f.range_mm, runs, w);
  zero_columns(f.reflectivity, runs, w);
  zero_columns(f.flags, runs, w);
  zero_columns(f.near_ir, runs, w);
  zero_columns(f.signal, runs, w);
  zero_columns(f.range2_mm, runs, w);
  zero_columns(f.reflectivity2, runs, w);
  zero_columns(f.flags2, runs, w);
  zero_columns(f.signal2, runs, w);
}

void read_ouster_pixels(const OusterPacketLayout& layout, const uint8_t* pixels, int column, OusterFrame& f) {
  const size_t stride = static_cast<size_t>(f.width);
  const size_t at = static_cast<size_t>(column);
  switch (layout.profile) {
    case OusterProfile::legacy: read_legacy(pixels, f.height, at, stride, f); break;
    case OusterProfile::single_return: read_single_return(pixels, f.height, at, stride, f); break;
    case OusterProfile::low_data_rate: read_low_data_rate(pixels, f.height, at, stride, f); break;
    case OusterProfile::dual_return: read_dual_return(pixels, f.height, at, stride, f); break;
  }
}

}  // namespace brickyard::drivers
