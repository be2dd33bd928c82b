#include "cli/capture_file.hpp"

#include "graph/diagnostics.hpp"
#include "io/bounded_read.hpp"

#include "drivers/common/pcap_reader.hpp"

namespace brickyard::fw::cli {

namespace {

// The drivers' own limits (ouster_source.cpp, gnss_source.cpp): what they replay, this reads.
constexpr std::size_t kMaxPcapBytes = std::size_t{4} << 30;
constexpr std::size_t kMaxLogBytes = std::size_t{1} << 30;

bool pcap_magic(const std::vector<std::uint8_t>& b) {
  if (b.size() < 4) return false;
  const std::uint32_t le = b[0] | b[1] << 8 | b[2] << 16 | static_cast<std::uint32_t>(b[3]) << 24;
  const std::uint32_t be = static_cast<std::uint32_t>(b[0]) << 24 | b[1] << 16 | b[2] << 8 | b[3];
  for (const std::uint32_t magic : {0xA1B2C3D4u, 0xA1B23C4Du})  // microseconds, nanoseconds
    if (le == magic || be == magic) return true;
  return le == 0x0A0D0D0Au;  // pcapng's section header: the same in both byte orders
}

}  // namespace

std::vector<std::uint8_t> read_whole(const std::string& path, std::size_t max_bytes) {
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path, max_bytes, bytes, error)) {
    // The reader's message starts with the path: said once, as the culprit.
    const std::string prefix = path + ": ";
    throw InvalidInput(path, error.rfind(prefix, 0) == 0 ? error.substr(prefix.size()) : error);
  }
  return bytes;
}

CaptureFile read_capture(const std::string& path) {
  CaptureFile f;
  f.path = path;
  f.bytes = read_whole(path, kMaxPcapBytes);
  f.kind = pcap_magic(f.bytes) ? CaptureKind::pcap : CaptureKind::gnss_log;
  if (f.kind == CaptureKind::gnss_log && f.bytes.size() > kMaxLogBytes)
    throw InvalidInput(path, "larger than " + std::to_string(kMaxLogBytes) + " bytes, the most a GNSS log is read");
  if (f.kind == CaptureKind::pcap) {
    const drivers::PcapReader reader(f.bytes);
    if (!reader.ok()) throw InvalidInput(path, reader.error());
  }
  return f;
}

}  // namespace brickyard::fw::cli
