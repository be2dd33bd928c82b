// libFuzzer harness: a capture file (pcap, as a LiDAR's packets are recorded and replayed)
// through the reader and IPv4 reassembly: any bytes must end as datagrams or a refused header,
// never a crash or a read past the file.
#include "drivers/common/pcap_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  brickyard::drivers::PcapReader reader(std::span<const std::uint8_t>(data, size));
  while (reader.next()) {
  }
  return 0;
}
