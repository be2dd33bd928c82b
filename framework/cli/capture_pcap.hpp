#pragma once
// What a pcap holds, by the drivers' pcap reader: its UDP datagrams per destination port, their
// times, and the reader's counters; with an Ouster sensor's metadata, the lidar port's packets
// through the drivers' decoder (its counters and the frames it assembled).
#include "drivers/common/ouster_packets.hpp"
#include "drivers/common/pcap_reader.hpp"

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace brickyard::fw::cli {

struct PortTally {
  std::uint64_t datagrams = 0, bytes = 0;  // bytes: the UDP payloads'
  std::int64_t first_ns = 0, last_ns = 0;
};

struct OusterFrameInfo {
  std::uint16_t frame_id = 0;
  int columns_expected = 0, columns_received = 0;
};

struct OusterInfo {
  std::string metadata_path;
  drivers::OusterMetadata metadata;
  std::uint16_t port = 0;  // the lidar port read: --port, else the metadata's udp_port_lidar
  drivers::OusterCounters counters;
  std::vector<OusterFrameInfo> frames;
};

struct PcapInfo {
  drivers::PcapCounters counters;
  std::map<std::uint16_t, PortTally> ports;
  PortTally all;  // every datagram: the capture's span and size
  std::optional<OusterInfo> ouster;
};

// Reads the metadata JSON; throws InvalidInput naming the file when it cannot be read or parsed.
drivers::OusterMetadata read_ouster_metadata(const std::string& path);

// `bytes` a pcap the reader accepts (read_capture checked it). With `ouster` set (its metadata
// and port), the packets to its port are decoded too.
PcapInfo tally_pcap(std::span<const std::uint8_t> bytes, std::optional<OusterInfo> ouster);

double rate_per_s(const PortTally& t);  // datagrams a second over the tally's span (0: too short to say)

}  // namespace brickyard::fw::cli
