#pragma once
// can-utils' candump log files (`candump -L`, what canplayer replays), read and written without
// the framework. One frame a line:
//   (1436509052.249713) can0 123#DEADBEEF       classic frame, 11-bit id, 0..8 bytes ('.' may separate bytes)
//   (1436509052.249713) can0 12345678#0011      extended id: 8 hex digits
//   (1436509052.249713) can0 123#R  123#R5      remote request, optionally its length
//   (1436509052.249713) can0 123##1DEADBEEF     CAN FD: a flags digit (BRS 1, ESI 2), then 0..64 bytes
// Error frames (8 digits with CAN_ERR_FLAG, 0x20000000) are counted and passed over. Bad lines
// come back with their line number; reading goes on. docs/can-dbc.md.
#include "can_frame.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::vehicle_interface {

struct CandumpRecord {
  uint64_t seconds = 0;  // of the timestamp, as candump writes it (since the epoch, or since its start)
  uint32_t microseconds = 0;
  std::string interface;  // "can0"
  CanFrame frame;

  bool operator==(const CandumpRecord&) const = default;
};

struct CandumpLine {
  std::optional<CandumpRecord> record;
  bool error_frame = false;  // a well-formed error frame: no record, no error
  std::string error;         // non-empty: what is wrong with the line
};

// One line, without its line end (a trailing '\r' is ignored).
CandumpLine parse_candump_line(std::string_view line);
// The line candump would write, without a line end: ids and data in upper-case hex.
std::string format_candump_line(const CandumpRecord& record);

struct CandumpLineError {
  size_t line = 0;  // 1-based
  std::string what;

  std::string text() const { return "line " + std::to_string(line) + ": " + what; }
};

struct CandumpLimits {
  size_t max_line_bytes = 1024;  // a CAN FD line with 64 separated bytes takes under 300
  size_t max_errors = 100;       // further bad lines are counted, not described
};

struct CandumpLog {
  std::vector<CandumpRecord> records;
  std::vector<CandumpLineError> errors;
  size_t bad_lines = 0;  // all of them, described or not
  size_t error_frames = 0;
};

// Every line of `text`; empty lines are passed over.
CandumpLog read_candump(std::string_view text, CandumpLimits limits = {});
// The records, one line each, each ended by '\n'.
std::string write_candump(const std::vector<CandumpRecord>& records);

// The files themselves: read whole (refused past max_bytes), written through a temporary file
// renamed into place. Errors name the path.
CandumpLog load_candump_file(const std::string& path, CandumpLimits limits = {}, size_t max_bytes = size_t{1} << 30);
bool save_candump_file(const std::string& path, const std::vector<CandumpRecord>& records, std::string* error);

}  // namespace brickyard::vehicle_interface
