#pragma once
// A reader of classic pcap captures (libpcap's file format: a 24-byte file header, then per packet
// a 16-byte record header and the captured bytes), framework-free: the capture's bytes in, its
// UDP/IPv4 datagrams out with their capture time and ports, no I/O, no exceptions on bad input.
// Links: Ethernet (with 802.1Q/802.1ad tags), raw IPv4, Linux cooked (SLL, SLL2). IPv4 fragments
// are reassembled (ipv4_reassembly.hpp). Anything else in the capture (ARP, IPv6, TCP) is counted
// and skipped; a record cut short or a header that cannot be right is counted and skipped. Both
// byte orders and both timestamp resolutions (microseconds, nanoseconds) are read. pcapng files
// are refused at open with an error saying so (none of the shipped captures is pcapng).
// Format sources: docs/drivers-formats.md, "Ouster LiDAR packets".
#include "ipv4_reassembly.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace brickyard::drivers {

struct UdpDatagram {
  int64_t time_ns = 0;  // capture time, Unix epoch
  uint32_t source_ip = 0;
  uint32_t destination_ip = 0;  // host order: 192.168.1.2 is 0xC0A80102
  uint16_t source_port = 0;
  uint16_t destination_port = 0;
  std::span<const uint8_t> payload;  // valid until the next call to next()
};

struct PcapCounters {
  uint64_t records = 0;        // packet records read
  uint64_t datagrams = 0;      // UDP datagrams handed out (a reassembled one counts once)
  uint64_t not_udp = 0;        // not UDP over IPv4 (ARP, IPv6, TCP, ...): skipped, not an error
  uint64_t truncated = 0;      // a record, or the headers in it, shorter than they say
  uint64_t malformed = 0;      // a header that cannot be right (IPv4 header under 20 bytes, ...)
  uint64_t fragments = 0;      // IPv4 fragments taken in
  uint64_t reassembled = 0;    // datagrams rebuilt from fragments
  uint64_t fragments_dropped = 0;  // fragments of datagrams never completed
  uint64_t refused() const { return truncated + malformed + fragments_dropped; }
};

class PcapReader {
 public:
  // `file` is the whole capture and must outlive the reader.
  explicit PcapReader(std::span<const uint8_t> file);

  // False when the file header is not one this reader reads; error() says why.
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  // The next UDP datagram; nothing at the end of the capture (or when !ok()).
  std::optional<UdpDatagram> next();
  const PcapCounters& counters() const { return counters_; }

 private:
  struct Record {
    int64_t time_ns;
    std::span<const uint8_t> bytes;
  };
  void read_file_header();
  std::optional<Record> next_record();
  std::optional<UdpDatagram> from_record(const Record& record);
  std::optional<std::span<const uint8_t>> ipv4_of_link(std::span<const uint8_t> frame);
  std::optional<UdpDatagram> from_ipv4(std::span<const uint8_t> packet, int64_t time_ns);
  std::optional<UdpDatagram> from_udp(std::span<const uint8_t> udp, uint32_t source, uint32_t destination,
                                      int64_t time_ns);
  uint32_t u32(size_t at) const;

  std::span<const uint8_t> file_;
  size_t at_ = 0;
  bool swapped_ = false;     // the file's byte order is not little-endian
  int64_t fraction_ns_ = 1000;  // nanoseconds per unit of a record's sub-second field
  uint32_t link_type_ = 0;
  std::string error_;
  Ipv4Reassembler reassembler_;
  bool finished_ = false;
  PcapCounters counters_;
};

}  // namespace brickyard::drivers
