#pragma once
// A capture read whole and told apart by its first bytes: a pcap (classic or pcapng's magic
// numbers: pcapng is then refused by the pcap reader, which says so) or else a GNSS log.
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::fw::cli {

enum class CaptureKind { pcap, gnss_log };

struct CaptureFile {
  std::string path;
  std::vector<std::uint8_t> bytes;
  CaptureKind kind = CaptureKind::gnss_log;
};

// Throws InvalidInput naming the file: missing, not a regular file (a FIFO or a device would
// never end), larger than the drivers read (4 GiB pcap, 1 GiB log), or a pcap the reader refuses.
CaptureFile read_capture(const std::string& path);

// Throws InvalidInput naming `path` when the file cannot be read (as above, at most `max_bytes`).
std::vector<std::uint8_t> read_whole(const std::string& path, std::size_t max_bytes);

}  // namespace brickyard::fw::cli
