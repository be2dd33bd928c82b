// candump log files on disk: the only I/O of the candump reader and writer.
#include "candump_log.hpp"

#include "io/bounded_read.hpp"

#include <cstdio>
#include <fstream>

namespace brickyard::vehicle_interface {

CandumpLog load_candump_file(const std::string& path, CandumpLimits limits, size_t max_bytes) {
  CandumpLog log;
  std::string error;
  std::ifstream in;
  if (io::is_regular_readable(path, error)) in.open(path, std::ios::binary);
  if (!in.is_open()) {
    log.errors.push_back({0, error.empty() ? "cannot open " + path : error});
    return log;
  }
  std::string text;
  char chunk[65536];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      log.errors.push_back({0, path + ": over " + std::to_string(max_bytes) + " bytes"});
      return log;
    }
  }
  return read_candump(text, limits);
}

// Written beside the file and renamed over it: a reader never sees half a log.
bool save_candump_file(const std::string& path, const std::vector<CandumpRecord>& records, std::string* error) {
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    const std::string text = write_candump(records);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) {
      if (error) *error = "cannot write " + part;
      std::remove(part.c_str());
      return false;
    }
  }
  if (std::rename(part.c_str(), path.c_str()) != 0) {
    if (error) *error = "cannot rename " + part + " to " + path;
    std::remove(part.c_str());
    return false;
  }
  return true;
}

}  // namespace brickyard::vehicle_interface
