#pragma once
// An Ouster sensor's metadata JSON named by a parameter, found, read (a regular file of at most
// 16 MiB) and parsed; BadInput naming the parameter and the file otherwise. Plugin-side (SDK):
// the driver (drivers.ouster_lidar) and the simulated sensor (sim.ouster) read it alike.
#include <brickyard/plugin.hpp>

#include "drivers/common/ouster_metadata.hpp"
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

}  // namespace brickyard::drivers
