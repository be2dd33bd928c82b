#include "ouster_packet_encode.hpp"

#include "little_endian.hpp"
#include "ouster_crc64.hpp"
#include "ouster_packet_format.hpp"

namespace brickyard::drivers {

namespace {

using le::put16;
using le::put32;
using le::put64;
using le::put_bytes;

template <typename T> T at_or_zero(const std::vector<T>& v, size_t i) { return i < v.size() ? v[i] : T{}; }

// A range in mm as its field holds it: 0 when it does not fit.
uint32_t field_range(uint32_t mm, uint32_t max) { return mm <= max ? mm : 0; }

// One pixel of row r of column c at p, as read_ouster_pixels reads it back.
void write_pixel(OusterProfile profile, const OusterFrame& f, size_t i, uint8_t* p) {
  switch (profile) {
    case OusterProfile::legacy:
      put32(p, field_range(f.range_mm[i], (1u << 20) - 1) | uint32_t{at_or_zero(f.flags, i)} << 28);
      p[4] = at_or_zero(f.reflectivity, i), put16(p + 6, at_or_zero(f.signal, i)), put16(p + 8, at_or_zero(f.near_ir, i));
      break;
    case OusterProfile::single_return:
      put32(p, field_range(f.range_mm[i], (1u << 19) - 1) | uint32_t{at_or_zero(f.flags, i) & 0x1Fu} << 19);
      p[4] = at_or_zero(f.reflectivity, i), put16(p + 6, at_or_zero(f.signal, i)), put16(p + 8, at_or_zero(f.near_ir, i));
      break;
    case OusterProfile::low_data_rate:
      put16(p, field_range((f.range_mm[i] + 4) / 8, (1u << 15) - 1) | uint32_t{at_or_zero(f.flags, i) & 1u} << 15);  // to the nearest 8 mm
      p[2] = at_or_zero(f.reflectivity, i), p[3] = static_cast<uint8_t>(at_or_zero(f.near_ir, i));
      break;
    case OusterProfile::dual_return:
      put32(p, field_range(f.range_mm[i], (1u << 19) - 1) | uint32_t{at_or_zero(f.flags, i) & 0x1Fu} << 19 |
                   uint32_t{at_or_zero(f.reflectivity, i)} << 24);
      put32(p + 4, field_range(at_or_zero(f.range2_mm, i), (1u << 19) - 1) | uint32_t{at_or_zero(f.flags2, i) & 0x1Fu} << 19 |
                       uint32_t{at_or_zero(f.reflectivity2, i)} << 24);
      put16(p + 8, at_or_zero(f.signal, i)), put16(p + 10, at_or_zero(f.signal2, i)), put16(p + 12, at_or_zero(f.near_ir, i));
      break;
  }
}

// Column c at p; `valid` false: its header alone, marked not valid (a column the sensor did not
// fire, or one past the window that fills the last packet).
void write_column(const OusterPacketLayout& l, const OusterFrame& f, int c, bool valid, uint8_t* p) {
  put64(p, at_or_zero(f.timestamp_ns, static_cast<size_t>(c)));
  put16(p + 8, static_cast<uint32_t>(c));
  if (l.profile == OusterProfile::legacy) {
    put16(p + 10, f.frame_id);
    put32(p + 12, at_or_zero(f.encoder_count, static_cast<size_t>(c)));
    put32(p + l.column_bytes() - 4, valid ? 0xFFFFFFFFu : 0u);
  } else {
    put16(p + 10, valid ? 1u : 0u);
  }
  if (!valid) return;
  uint8_t* pixel = p + l.column_header_bytes;
  for (int r = 0; r < f.height; ++r, pixel += l.pixel_bytes) write_pixel(l.profile, f, f.pixel(r, c), pixel);
}

void write_packet_header(const OusterFrame& f, const OusterMetadata& m, uint8_t* p) {
  put16(p, 1);
  put16(p + 2, f.frame_id);
  put_bytes(p + 4, m.initialization_id, 3);
  put_bytes(p + 7, m.serial_number, 5);
}

}  // namespace

int ouster_packets_per_frame(const OusterMetadata& m) {
  const int per_packet = ouster_packet_layout(m).columns_per_packet;
  return per_packet > 0 ? (m.columns_in_window() + per_packet - 1) / per_packet : 0;
}

std::vector<uint8_t> encode_ouster_packet(const OusterFrame& frame, const OusterMetadata& m, int index) {
  const OusterPacketLayout l = ouster_packet_layout(m);
  const int window = m.columns_in_window(), first = index * l.columns_per_packet;
  std::vector<uint8_t> packet(l.packet_bytes(), 0);
  if (l.header_bytes) write_packet_header(frame, m, packet.data());
  for (int k = 0; k < l.columns_per_packet; ++k) {
    // Past the window's end a packet is filled with the columns after it, marked not valid.
    const int c = (m.column_window_first + first + k) % m.columns_per_frame;
    uint8_t* column = packet.data() + l.header_bytes + static_cast<size_t>(k) * l.column_bytes();
    write_column(l, frame, c, first + k < window && at_or_zero(frame.received, static_cast<size_t>(c)) != 0, column);
  }
  if (m.packet_crc) put64(packet.data() + packet.size() - 8, crc64_xz(packet.data(), packet.size() - 8));
  return packet;
}

void encode_ouster_packets(const OusterFrame& frame, const OusterMetadata& m, std::vector<std::vector<uint8_t>>& packets) {
  for (int i = 0, n = ouster_packets_per_frame(m); i < n; ++i) packets.push_back(encode_ouster_packet(frame, m, i));
}

}  // namespace brickyard::drivers
