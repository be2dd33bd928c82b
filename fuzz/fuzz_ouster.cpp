// libFuzzer harness: UDP payloads from an Ouster LiDAR's port through the packet decoder, the
// frame assembly and the points, for each shipped sensor's metadata (data/lidar_packets; the
// input's first byte picks one). The rest of the input is packets, each a 2-byte little-endian
// length and its bytes: any of them must end as frames or counted refusals, never a crash. Each
// packet is also read as an IMU packet (port 7503's): read or refused, never a crash.
#include "drivers/common/ouster_imu.hpp"
#include "drivers/common/ouster_metadata.hpp"
#include "drivers/common/ouster_packets.hpp"
#include "drivers/common/ouster_xyz.hpp"

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace brickyard::drivers;

std::vector<OusterMetadata> shipped_metadata() {
  std::vector<OusterMetadata> out;
  for (const char* name : {"OS-0-32-U1_v2.2.0_1024x10.json", "OS-1-32-G_v2.1.1_1024x10.json", "OS-1-128_v2.3.0_1024x10.json",
                           "OS-2-128-U1_v2.3.0_1024x10.json", "crc_test.json"}) {
    std::ifstream f(std::string(BRICKYARD_SOURCE_DIR) + "/data/lidar_packets/" + name);
    std::stringstream text;
    text << f.rdbuf();
    OusterMetadata m;
    std::string error;
    if (parse_ouster_metadata(text.str(), m, error)) out.push_back(std::move(m));
  }
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<OusterMetadata> sensors = shipped_metadata();
  if (size == 0 || sensors.empty()) return 0;
  const OusterMetadata& metadata = sensors[data[0] % sensors.size()];
  static std::vector<OusterXyzTable> tables;
  if (tables.empty())
    for (const OusterMetadata& m : sensors) tables.emplace_back(m);
  const OusterXyzTable& table = tables[data[0] % sensors.size()];
  OusterLidarDecoder decoder(metadata);
  OusterCloud cloud;
  std::size_t at = 1;
  auto drain = [&] {
    while (auto frame = decoder.next()) {
      ouster_frame_to_cloud(*frame, table, cloud);
      decoder.recycle(std::move(*frame));
    }
  };
  while (at + 2 <= size) {
    const std::size_t n = std::min<std::size_t>(data[at] | data[at + 1] << 8, size - at - 2);
    decoder.feed(data + at + 2, n);
    if (const auto imu = read_ouster_imu_packet(data + at + 2, n)) ouster_imu_in_sensor_frame(*imu, metadata.imu_to_sensor);
    drain();
    at += 2 + n;
  }
  decoder.finish();
  drain();
  return 0;
}
