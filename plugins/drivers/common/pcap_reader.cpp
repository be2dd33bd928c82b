#include "pcap_reader.hpp"

namespace brickyard::drivers {

namespace {

constexpr size_t kFileHeaderBytes = 24;
constexpr size_t kRecordHeaderBytes = 16;
constexpr uint32_t kMagicMicroseconds = 0xA1B2C3D4u;
constexpr uint32_t kMagicNanoseconds = 0xA1B23C4Du;
constexpr uint32_t kPcapngSectionHeader = 0x0A0D0D0Au;

// Link types (tcpdump.org/linktypes.html).
constexpr uint32_t kLinkEthernet = 1;
constexpr uint32_t kLinkRaw = 101;
constexpr uint32_t kLinkLinuxSll = 113;
constexpr uint32_t kLinkIpv4 = 228;
constexpr uint32_t kLinkLinuxSll2 = 276;

constexpr uint16_t kEtherIpv4 = 0x0800;
constexpr uint16_t kEtherVlan = 0x8100;
constexpr uint16_t kEtherQinQ = 0x88A8;
constexpr uint8_t kProtocolUdp = 17;

uint32_t swap32(uint32_t v) { return (v >> 24) | ((v >> 8) & 0xFF00u) | ((v << 8) & 0xFF0000u) | (v << 24); }
uint16_t be16(const uint8_t* p) { return static_cast<uint16_t>(p[0] << 8 | p[1]); }
uint32_t be32(const uint8_t* p) { return static_cast<uint32_t>(be16(p)) << 16 | be16(p + 2); }

}  // namespace

PcapReader::PcapReader(std::span<const uint8_t> file) : file_(file) { read_file_header(); }

uint32_t PcapReader::u32(size_t at) const {
  const uint8_t* p = file_.data() + at;
  uint32_t v = p[0] | p[1] << 8 | p[2] << 16 | static_cast<uint32_t>(p[3]) << 24;
  return swapped_ ? swap32(v) : v;
}

void PcapReader::read_file_header() {
  if (file_.size() < kFileHeaderBytes) {
    error_ = "not a pcap file: shorter than its 24-byte header";
    return;
  }
  uint32_t magic = u32(0);
  if (magic == swap32(kMagicMicroseconds) || magic == swap32(kMagicNanoseconds)) {
    swapped_ = true;
    magic = swap32(magic);
  }
  if (magic == kPcapngSectionHeader) {
    error_ = "a pcapng file: only classic pcap is read (editcap -F pcap converts)";
    return;
  }
  if (magic != kMagicMicroseconds && magic != kMagicNanoseconds) {
    error_ = "not a pcap file: unknown magic number";
    return;
  }
  fraction_ns_ = magic == kMagicNanoseconds ? 1 : 1000;
  link_type_ = u32(20) & 0xFFFFu;  // the top bits may say how long a frame check sequence is
  if (link_type_ != kLinkEthernet && link_type_ != kLinkRaw && link_type_ != kLinkIpv4 &&
      link_type_ != kLinkLinuxSll && link_type_ != kLinkLinuxSll2) {
    error_ = "pcap link type " + std::to_string(link_type_) + " is not read (Ethernet, raw IPv4, Linux SLL are)";
    return;
  }
  at_ = kFileHeaderBytes;
}

std::optional<UdpDatagram> PcapReader::next() {
  if (!ok()) return std::nullopt;
  while (auto record = next_record()) {
    if (auto datagram = from_record(*record)) {
      ++counters_.datagrams;
      return datagram;
    }
  }
  if (!finished_) {  // datagrams still missing fragments at the end never will be complete
    finished_ = true;
    reassembler_.finish();
    counters_.fragments_dropped = reassembler_.fragments_dropped();
  }
  return std::nullopt;
}

std::optional<PcapReader::Record> PcapReader::next_record() {
  if (at_ >= file_.size()) return std::nullopt;
  if (file_.size() - at_ < kRecordHeaderBytes) {
    ++counters_.truncated;  // a record header cut off by the end of the file
    at_ = file_.size();
    return std::nullopt;
  }
  const uint64_t seconds = u32(at_);
  const uint64_t fraction = u32(at_ + 4);
  const size_t captured = u32(at_ + 8);
  at_ += kRecordHeaderBytes;
  ++counters_.records;
  if (captured > file_.size() - at_) {
    ++counters_.truncated;  // the record runs past the end of the file
    at_ = file_.size();
    return std::nullopt;
  }
  Record r{static_cast<int64_t>(seconds * 1000000000ull + fraction * static_cast<uint64_t>(fraction_ns_)),
           file_.subspan(at_, captured)};
  at_ += captured;
  return r;
}

std::optional<UdpDatagram> PcapReader::from_record(const Record& record) {
  auto packet = ipv4_of_link(record.bytes);
  if (!packet) return std::nullopt;
  return from_ipv4(*packet, record.time_ns);
}

// The IPv4 packet inside a link-layer frame; nothing (counted) when the frame carries another
// protocol or is cut short.
std::optional<std::span<const uint8_t>> PcapReader::ipv4_of_link(std::span<const uint8_t> frame) {
  size_t type_at = 0;
  switch (link_type_) {
    case kLinkRaw:
    case kLinkIpv4:
      if (!frame.empty() && (frame[0] >> 4) == 4) return frame;
      ++counters_.not_udp;
      return std::nullopt;
    case kLinkLinuxSll: type_at = 14; break;
    case kLinkLinuxSll2: type_at = 0; break;
    default: type_at = 12; break;  // Ethernet: two addresses, then the EtherType
  }
  size_t payload_at = link_type_ == kLinkLinuxSll2 ? 20 : type_at + 2;
  if (frame.size() < payload_at) {
    ++counters_.truncated;
    return std::nullopt;
  }
  uint16_t type = be16(frame.data() + type_at);
  while (link_type_ == kLinkEthernet && (type == kEtherVlan || type == kEtherQinQ)) {
    if (frame.size() < payload_at + 4) {
      ++counters_.truncated;
      return std::nullopt;
    }
    type = be16(frame.data() + payload_at + 2);  // a 4-byte tag, then the next EtherType
    payload_at += 4;
  }
  if (type != kEtherIpv4) {
    ++counters_.not_udp;
    return std::nullopt;
  }
  return frame.subspan(payload_at);
}

std::optional<UdpDatagram> PcapReader::from_ipv4(std::span<const uint8_t> ip, int64_t time_ns) {
  if (ip.size() < 20) {
    ++counters_.truncated;
    return std::nullopt;
  }
  const size_t header_bytes = static_cast<size_t>(ip[0] & 0x0F) * 4;
  const size_t total = be16(ip.data() + 2);
  if ((ip[0] >> 4) != 4 || header_bytes < 20 || total < header_bytes) {
    ++counters_.malformed;
    return std::nullopt;
  }
  if (total > ip.size()) {  // captured with a snap length below the packet's size
    ++counters_.truncated;
    return std::nullopt;
  }
  if (ip[9] != kProtocolUdp) {
    ++counters_.not_udp;
    return std::nullopt;
  }
  const uint32_t source = be32(ip.data() + 12);
  const uint32_t destination = be32(ip.data() + 16);
  const uint16_t flags_offset = be16(ip.data() + 6);
  const bool more_fragments = (flags_offset & 0x2000u) != 0;
  const size_t offset = static_cast<size_t>(flags_offset & 0x1FFFu) * 8;
  std::span<const uint8_t> payload = ip.subspan(header_bytes, total - header_bytes);  // no link padding
  if (!more_fragments && offset == 0) return from_udp(payload, source, destination, time_ns);

  ++counters_.fragments;
  Ipv4FragmentKey key{source, destination, be16(ip.data() + 4), ip[9]};
  auto whole = reassembler_.add(key, offset, more_fragments, payload);
  counters_.fragments_dropped = reassembler_.fragments_dropped();
  if (!whole) return std::nullopt;
  ++counters_.reassembled;
  return from_udp(*whole, source, destination, time_ns);  // stamped with its last fragment's time
}

std::optional<UdpDatagram> PcapReader::from_udp(std::span<const uint8_t> udp, uint32_t source,
                                                uint32_t destination, int64_t time_ns) {
  if (udp.size() < 8) {
    ++counters_.truncated;
    return std::nullopt;
  }
  const size_t length = be16(udp.data() + 4);
  if (length < 8 || length > udp.size()) {
    ++counters_.malformed;
    return std::nullopt;
  }
  UdpDatagram d;
  d.time_ns = time_ns;
  d.source_ip = source;
  d.destination_ip = destination;
  d.source_port = be16(udp.data());
  d.destination_port = be16(udp.data() + 2);
  d.payload = udp.subspan(8, length - 8);
  return d;
}

}  // namespace brickyard::drivers
