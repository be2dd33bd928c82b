#pragma once
// Test helpers for the Ouster decoder: the shipped captures read and decoded whole, and the
// vendor's digests of decoded fields recomputed from our frames. A digest is the MD5 of one field's
// values laid end to end in little-endian: "scans" hash a frame's staggered image row by row
// (row-major, height x width), "packet_hash" hashes each packet's pixels row by row within the
// packet (height x columns_per_packet), packet after packet; per-column fields are in column order
// in both. Each field's type is in scan_digests() and packet_digests() below (found by matching
// the digests, not read from any code). docs/drivers-formats.md, "What the digests contain".
#include "drivers/common/ouster_metadata.hpp"
#include "drivers/common/ouster_packets.hpp"
#include "drivers/common/pcap_reader.hpp"
#include "md5.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace brickyard::drivers::test {

inline std::string lidar_data_path(const std::string& name) {
  return std::string(BRICKYARD_SOURCE_DIR) + "/data/lidar_packets/" + name;
}

inline std::vector<uint8_t> read_bytes(const std::string& name) {
  std::ifstream in(lidar_data_path(name), std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot open " << lidar_data_path(name);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string read_text(const std::string& name) {
  std::vector<uint8_t> bytes = read_bytes(name);
  return std::string(bytes.begin(), bytes.end());
}

inline OusterMetadata load_metadata(const std::string& name) {
  OusterMetadata m;
  std::string error;
  EXPECT_TRUE(parse_ouster_metadata(read_text(name), m, error)) << name << ": " << error;
  return m;
}

struct DecodedCapture {
  OusterMetadata metadata;
  std::vector<OusterFrame> frames;
  OusterCounters counters;
  PcapCounters pcap;
  std::vector<std::vector<uint8_t>> lidar_payloads;  // in capture order
  size_t other_datagrams = 0;                        // IMU packets (port 7503)
};

// Every datagram to the metadata's lidar port through one decoder, then finish().
inline DecodedCapture decode_payloads(const OusterMetadata& metadata, const std::vector<std::vector<uint8_t>>& payloads,
                                      OusterDecoderOptions options = {}) {
  DecodedCapture out;
  out.metadata = metadata;
  out.lidar_payloads = payloads;
  OusterLidarDecoder decoder(metadata, options);
  for (const auto& p : payloads) {
    decoder.feed(p.data(), p.size());
    while (auto f = decoder.next()) out.frames.push_back(std::move(*f));
  }
  decoder.finish();
  while (auto f = decoder.next()) out.frames.push_back(std::move(*f));
  out.counters = decoder.counters();
  return out;
}

inline DecodedCapture decode_capture(const std::string& pcap_name, const std::string& json_name,
                                     OusterDecoderOptions options = {}) {
  OusterMetadata metadata = load_metadata(json_name);
  std::vector<uint8_t> file = read_bytes(pcap_name);
  PcapReader reader(file);
  EXPECT_TRUE(reader.ok()) << pcap_name << ": " << reader.error();
  std::vector<std::vector<uint8_t>> lidar;
  size_t other = 0;
  while (auto d = reader.next()) {
    if (d->destination_port == metadata.udp_port_lidar) {
      lidar.emplace_back(d->payload.begin(), d->payload.end());
    } else {
      ++other;
    }
  }
  DecodedCapture out = decode_payloads(metadata, lidar, options);
  out.pcap = reader.counters();
  out.other_datagrams = other;
  return out;
}

// --- the vendor's digests, recomputed ---------------------------------------------------------

template <typename Stored, typename T>
std::string md5_as(const std::vector<T>& values, const std::vector<size_t>& order) {
  Md5 md5;
  for (size_t i : order) {
    Stored v = static_cast<Stored>(values[i]);
    uint8_t bytes[sizeof(Stored)];
    for (size_t b = 0; b < sizeof(Stored); ++b) bytes[b] = static_cast<uint8_t>(static_cast<uint64_t>(v) >> (8 * b));
    md5.update(bytes, sizeof bytes);
  }
  return md5.hex();
}

inline std::vector<size_t> identity_order(size_t n) {
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  return order;
}

// Pixel indices in packet order: packet k holds columns [k * cpp, (k + 1) * cpp), row by row.
inline std::vector<size_t> packet_pixel_order(const OusterFrame& f, int columns_per_packet) {
  std::vector<size_t> order;
  for (int first = 0; first < f.width; first += columns_per_packet) {
    for (int row = 0; row < f.height; ++row) {
      for (int c = first; c < first + columns_per_packet; ++c) order.push_back(f.pixel(row, c));
    }
  }
  return order;
}

// Our frame's digest of each field the vendor's file names, in the vendor's types.
inline std::map<std::string, std::string> scan_digests(const OusterFrame& f) {
  std::vector<uint32_t> ids(static_cast<size_t>(f.width));
  for (int c = 0; c < f.width; ++c) ids[c] = f.received[c] ? static_cast<uint32_t>(c) : 0u;
  const std::vector<size_t> columns = identity_order(static_cast<size_t>(f.width));
  const std::vector<size_t> pixels = identity_order(f.range_mm.size());
  std::map<std::string, std::string> d;
  d["TIMESTAMP"] = md5_as<uint64_t>(f.timestamp_ns, columns);
  d["MEASUREMENT_ID"] = md5_as<uint16_t>(ids, columns);
  d["STATUS"] = md5_as<uint64_t>(f.status, columns);
  d["ENCODER_COUNT"] = md5_as<uint64_t>(f.encoder_count, columns);
  d["RANGE"] = md5_as<uint32_t>(f.range_mm, pixels);
  d["REFLECTIVITY"] = md5_as<uint8_t>(f.reflectivity, pixels);
  d["NEAR_IR"] = md5_as<uint16_t>(f.near_ir, pixels);
  if (!f.signal.empty()) d["SIGNAL"] = md5_as<uint16_t>(f.signal, pixels);
  if (!f.range2_mm.empty()) {
    d["RANGE2"] = md5_as<uint32_t>(f.range2_mm, pixels);
    d["REFLECTIVITY2"] = md5_as<uint8_t>(f.reflectivity2, pixels);
    d["SIGNAL2"] = md5_as<uint16_t>(f.signal2, pixels);
  }
  return d;
}

// RAW32_WORDk: the k-th 32-bit word of each pixel as the packets carried it.
inline std::string raw_word_digest(const std::vector<std::vector<uint8_t>>& packets, const OusterPacketLayout& l,
                                   int word) {
  Md5 md5;
  for (const auto& p : packets) {
    for (int row = 0; row < l.pixels_per_column; ++row) {
      for (int c = 0; c < l.columns_per_packet; ++c) {
        size_t at = l.header_bytes + c * l.column_bytes() + l.column_header_bytes + row * l.pixel_bytes + 4 * word;
        md5.update(p.data() + at, 4);
      }
    }
  }
  return md5.hex();
}

inline std::map<std::string, std::string> packet_digests(const DecodedCapture& capture) {
  const OusterFrame& f = capture.frames.front();
  const OusterPacketLayout layout = ouster_packet_layout(capture.metadata);
  const bool legacy = layout.profile == OusterProfile::legacy;
  const std::vector<size_t> columns = identity_order(static_cast<size_t>(f.width));
  const std::vector<size_t> pixels = packet_pixel_order(f, layout.columns_per_packet);
  std::vector<uint32_t> ids(static_cast<size_t>(f.width)), frame_ids(static_cast<size_t>(f.width));
  for (int c = 0; c < f.width; ++c) {
    ids[c] = static_cast<uint32_t>(c);
    frame_ids[c] = legacy ? f.frame_id : 0u;  // only LEGACY columns carry the frame id
  }
  std::map<std::string, std::string> d;
  d["TIMESTAMP"] = md5_as<uint64_t>(f.timestamp_ns, columns);
  d["ENCODER_COUNT"] = md5_as<uint32_t>(f.encoder_count, columns);
  d["MEASUREMENT_ID"] = md5_as<uint16_t>(ids, columns);
  d["STATUS"] = md5_as<uint32_t>(f.status, columns);
  d["FRAME_ID"] = md5_as<uint16_t>(frame_ids, columns);
  d["RANGE"] = md5_as<uint32_t>(f.range_mm, pixels);
  d["REFLECTIVITY"] = md5_as<uint8_t>(f.reflectivity, pixels);
  d["NEAR_IR"] = md5_as<uint16_t>(f.near_ir, pixels);
  d["FLAGS"] = md5_as<uint8_t>(f.flags, pixels);
  if (!f.signal.empty()) d["SIGNAL"] = md5_as<uint16_t>(f.signal, pixels);
  if (!f.range2_mm.empty()) {
    d["RANGE2"] = md5_as<uint32_t>(f.range2_mm, pixels);
    d["REFLECTIVITY2"] = md5_as<uint8_t>(f.reflectivity2, pixels);
    d["SIGNAL2"] = md5_as<uint16_t>(f.signal2, pixels);
    d["FLAGS2"] = md5_as<uint8_t>(f.flags2, pixels);
  }
  if (!legacy) {
    for (size_t k = 0; k < layout.pixel_bytes / 4; ++k) {
      d["RAW32_WORD" + std::to_string(k + 1)] = raw_word_digest(capture.lidar_payloads, layout, static_cast<int>(k));
    }
  }
  return d;
}

}  // namespace brickyard::drivers::test
