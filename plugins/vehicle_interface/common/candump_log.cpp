// The candump log line, as can-utils' lib.h documents parse_canframe() and candump writes it.
#include "candump_log.hpp"

#include <cstdio>

namespace brickyard::vehicle_interface {

namespace {

constexpr uint32_t kErrorFrameFlag = 0x20000000;  // linux/can.h CAN_ERR_FLAG
constexpr size_t kMaxInterfaceBytes = 15;         // IFNAMSIZ 16, with its terminating zero

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// The next run of non-blank characters; `rest` moves past it and the blanks after it.
std::string_view next_field(std::string_view& rest) {
  size_t end = 0;
  while (end < rest.size() && !is_blank(rest[end])) ++end;
  const std::string_view field = rest.substr(0, end);
  while (end < rest.size() && is_blank(rest[end])) ++end;
  rest.remove_prefix(end);
  return field;
}

// "(seconds.micros)": 1 to 19 digits, a point, exactly 6 digits.
std::string read_timestamp(std::string_view field, CandumpRecord& r) {
  if (field.size() < 10 || field.front() != '(' || field.back() != ')') return "timestamp is not (seconds.microseconds)";
  const std::string_view inside = field.substr(1, field.size() - 2);
  const size_t point = inside.find('.');
  if (point == std::string_view::npos || point == 0 || point > 19 || inside.size() - point - 1 != 6)
    return "timestamp is not (seconds.microseconds), 6 digits after the point";
  uint64_t seconds = 0, micros = 0;
  for (size_t i = 0; i < inside.size(); ++i) {
    if (i == point) continue;
    if (inside[i] < '0' || inside[i] > '9') return "timestamp has a character other than digits";
    uint64_t& part = i < point ? seconds : micros;
    part = part * 10 + static_cast<uint64_t>(inside[i] - '0');
  }
  r.seconds = seconds;
  r.microseconds = static_cast<uint32_t>(micros);
  return "";
}

// Hex bytes, optionally separated by single '.', at most `max_bytes` of them.
std::string read_data(std::string_view hex, size_t max_bytes, CanFrame& f) {
  size_t count = 0;
  for (size_t i = 0; i < hex.size();) {
    if (hex[i] == '.' && count > 0 && i + 1 < hex.size() && hex[i + 1] != '.') {
      ++i;
      continue;
    }
    if (i + 1 >= hex.size() || hex_value(hex[i]) < 0 || hex_value(hex[i + 1]) < 0)
      return "data is not pairs of hex digits";
    if (count == max_bytes) return "more than " + std::to_string(max_bytes) + " data bytes";
    f.data[count++] = static_cast<uint8_t>(hex_value(hex[i]) * 16 + hex_value(hex[i + 1]));
    i += 2;
  }
  f.length = static_cast<uint8_t>(count);
  return "";
}

// 3 hex digits: an 11-bit id; 8: a 29-bit id, or an error frame (CAN_ERR_FLAG set).
std::string read_id(std::string_view hex, CanFrame& f, bool& error_frame) {
  if (hex.size() != 3 && hex.size() != 8) return "id is not 3 or 8 hex digits";
  uint32_t id = 0;
  for (char c : hex) {
    if (hex_value(c) < 0) return "id is not hex digits";
    id = id * 16 + static_cast<uint32_t>(hex_value(c));
  }
  f.extended = hex.size() == 8;
  error_frame = f.extended && (id & kErrorFrameFlag) != 0;
  if (error_frame) return "";
  if (id > (f.extended ? kExtendedIdMax : kStandardIdMax)) return f.extended ? "id wider than 29 bits" : "id over 7FF";
  f.id = id;
  return "";
}

// After the id: "#data", "#R", "#R<len>", or "##<flags>data".
std::string read_payload(std::string_view text, CanFrame& f) {
  if (text.size() >= 2 && text[1] == '#') {
    if (text.size() < 3 || hex_value(text[2]) < 0) return "CAN FD frame without its flags digit";
    f.fd = true;
    f.fd_flags = static_cast<uint8_t>(hex_value(text[2]));
    const std::string problem = read_data(text.substr(3), kFdMaxBytes, f);
    if (problem.empty() && !is_fd_length(f.length)) return std::to_string(f.length) + " bytes is not a CAN FD length";
    return problem;
  }
  if (text.size() >= 2 && (text[1] == 'R' || text[1] == 'r')) {
    f.remote = true;
    if (text.size() == 2) return "";
    if (text.size() != 3 || text[2] < '0' || text[2] > '8') return "remote frame's length is not one digit 0 to 8";
    f.length = static_cast<uint8_t>(text[2] - '0');
    return "";
  }
  return read_data(text.substr(1), kClassicMaxBytes, f);
}

std::string read_frame(std::string_view field, CanFrame& f, bool& error_frame) {
  const size_t hash = field.find('#');
  if (hash == std::string_view::npos) return "frame is not id#data";
  if (std::string problem = read_id(field.substr(0, hash), f, error_frame); !problem.empty()) return problem;
  if (std::string problem = read_payload(field.substr(hash), f); !problem.empty()) return problem;
  if (error_frame && (f.fd || f.remote)) return "an error frame is neither remote nor CAN FD";
  return "";
}

}  // namespace

CandumpLine parse_candump_line(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  CandumpLine out;
  CandumpRecord r;
  std::string_view rest = line;
  while (!rest.empty() && is_blank(rest.front())) rest.remove_prefix(1);
  const std::string_view time = next_field(rest), interface = next_field(rest), frame = next_field(rest);
  if (frame.empty() || !rest.empty()) {
    out.error = "line is not (time) interface frame";
  } else if (interface.size() > kMaxInterfaceBytes) {
    out.error = "interface name longer than 15 characters";
  } else if (std::string problem = read_timestamp(time, r); !problem.empty()) {
    out.error = problem;
  } else if (std::string frame_problem = read_frame(frame, r.frame, out.error_frame); !frame_problem.empty()) {
    out.error = frame_problem;
    out.error_frame = false;
  } else if (!out.error_frame) {
    r.interface = std::string(interface);
    out.record = std::move(r);
  }
  return out;
}

std::string format_candump_line(const CandumpRecord& r) {
  const CanFrame& f = r.frame;
  char head[64];
  std::snprintf(head, sizeof head, "(%010llu.%06u) ", static_cast<unsigned long long>(r.seconds), r.microseconds % 1000000);
  std::string line = head + r.interface + ' ';
  char hex[16];
  std::snprintf(hex, sizeof hex, f.extended ? "%08X" : "%03X", f.id);
  line += hex;
  if (f.remote) {
    line += "#R";
    if (f.length > 0) line += std::to_string(f.length);
    return line;
  }
  if (f.fd) std::snprintf(hex, sizeof hex, "##%X", f.fd_flags & 0xF), line += hex;
  else line += '#';
  for (size_t i = 0; i < f.length && i < f.data.size(); ++i) {
    std::snprintf(hex, sizeof hex, "%02X", f.data[i]);
    line += hex;
  }
  return line;
}

CandumpLog read_candump(std::string_view text, CandumpLimits limits) {
  CandumpLog log;
  size_t line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    CandumpLine parsed;
    if (line.size() > limits.max_line_bytes) parsed.error = "line longer than " + std::to_string(limits.max_line_bytes) + " bytes";
    else parsed = parse_candump_line(line);
    if (parsed.record) log.records.push_back(std::move(*parsed.record));
    if (parsed.error_frame) ++log.error_frames;
    if (parsed.error.empty()) continue;
    ++log.bad_lines;
    if (log.errors.size() < limits.max_errors) log.errors.push_back({line_number, std::move(parsed.error)});
  }
  return log;
}

std::string write_candump(const std::vector<CandumpRecord>& records) {
  std::string text;
  for (const CandumpRecord& r : records) text += format_candump_line(r) + '\n';
  return text;
}

}  // namespace brickyard::vehicle_interface
