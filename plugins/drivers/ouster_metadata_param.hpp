#pragma once
// An Ouster sensor's metadata JSON named by a parameter, found, read (a regular file of at most
// 16 MiB) and parsed; BadInput naming the parameter and the file otherwise. Plugin-side (SDK):
// the drivers (drivers.ouster_lidar, drivers.ouster_imu) and the simulated sensor (sim.ouster)
// read it alike.
#include <brickyard/plugin.hpp>

#include "drivers/common/ouster_metadata.hpp"
#include "drivers/source_param.hpp"
#include "io/bounded_read.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

template <class Files> OusterMetadata read_ouster_metadata_param(const Files& files, const std::string& name, const std::string& param) {
  const std::string path = files.find_file(name);
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path, 16 << 20, bytes, error)) throw BadInput("parameter '" + param + "': " + error);
  OusterMetadata m;
  if (!parse_ouster_metadata(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), m, error))
    throw BadInput("parameter '" + param + "': " + path + ": " + error);
  return m;
}

// An Ouster node's wire: its `source` (udp:// or pcap://, the capture found) and its sensor's
// `metadata`, into the settings' source, capture_path and metadata. `reads`: what the node reads,
// for the message ("an Ouster sensor's IMU").
template <class Files, class SourceSettings>
void read_ouster_wire(const Files& files, const std::string& source, const std::string& metadata, const std::string& reads, SourceSettings& o) {
  o.source = parse_source_param(source);
  if (o.source.kind != SourceSpec::Kind::udp && o.source.kind != SourceSpec::Kind::pcap)
    throw BadInput("parameter 'source': " + source + ": " + reads + " is read from udp:// or pcap://");
  if (o.source.kind == SourceSpec::Kind::pcap) o.capture_path = files.find_file(o.source.path);
  o.metadata = read_ouster_metadata_param(files, metadata, "metadata");
}

}  // namespace brickyard::drivers
