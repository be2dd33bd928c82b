#include "cli/capture_pcap.hpp"

#include "cli/capture_file.hpp"
#include "graph/diagnostics.hpp"

#include <algorithm>
#include <string_view>

namespace brickyard::fw::cli {

namespace {

constexpr std::size_t kMaxMetadataBytes = std::size_t{16} << 20;  // as drivers.ouster_lidar reads it

void count(PortTally& t, const drivers::UdpDatagram& d) {
  t.first_ns = t.datagrams ? std::min(t.first_ns, d.time_ns) : d.time_ns;
  t.last_ns = t.datagrams ? std::max(t.last_ns, d.time_ns) : d.time_ns;
  ++t.datagrams;
  t.bytes += d.payload.size();
}

void take_frames(drivers::OusterLidarDecoder& decoder, OusterInfo& out) {
  while (auto f = decoder.next()) {
    out.frames.push_back({f->frame_id, f->columns_expected, f->columns_received});
    decoder.recycle(std::move(*f));
  }
}

}  // namespace

drivers::OusterMetadata read_ouster_metadata(const std::string& path) {
  const std::vector<std::uint8_t> bytes = read_whole(path, kMaxMetadataBytes);
  drivers::OusterMetadata m;
  std::string error;
  if (!drivers::parse_ouster_metadata(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), m, error))
    throw InvalidInput(path, error);
  return m;
}

PcapInfo tally_pcap(std::span<const std::uint8_t> bytes, std::optional<OusterInfo> ouster) {
  PcapInfo info;
  drivers::PcapReader reader(bytes);
  std::optional<drivers::OusterLidarDecoder> decoder;
  if (ouster) decoder.emplace(ouster->metadata);
  while (auto d = reader.next()) {
    count(info.ports[d->destination_port], *d);
    count(info.all, *d);
    if (decoder && d->destination_port == ouster->port) {
      decoder->feed(d->payload.data(), d->payload.size());
      take_frames(*decoder, *ouster);
    }
  }
  info.counters = reader.counters();
  if (decoder) {
    decoder->finish();  // the last rotation, complete or not, as the driver hands it out
    take_frames(*decoder, *ouster);
    ouster->counters = decoder->counters();
    info.ouster = std::move(ouster);
  }
  return info;
}

double rate_per_s(const PortTally& t) {
  const double span_s = static_cast<double>(t.last_ns - t.first_ns) * 1e-9;
  return t.datagrams > 1 && span_s > 0 ? static_cast<double>(t.datagrams - 1) / span_s : 0.0;
}

}  // namespace brickyard::fw::cli
