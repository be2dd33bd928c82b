#include "text_fields.hpp"

#include <charconv>
#include <cmath>

namespace brickyard::drivers {

bool split_fields(std::string_view text, std::vector<std::string_view>& fields, bool quoted_strings) {
  fields.clear();
  size_t begin = 0;
  bool in_quotes = false;
  for (size_t i = 0; i < text.size(); ++i) {
    if (quoted_strings && text[i] == '"') in_quotes = !in_quotes;
    else if (text[i] == ',' && !in_quotes) {
      fields.push_back(text.substr(begin, i - begin));
      begin = i + 1;
    }
  }
  fields.push_back(text.substr(begin));
  return !in_quotes;
}

bool read_double(std::string_view field, double& value) {
  if (field.empty()) return false;
  const char* end = field.data() + field.size();
  auto [ptr, ec] = std::from_chars(field.data(), end, value, std::chars_format::general);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

bool read_float(std::string_view field, float& value) {
  double wide = 0;
  if (!read_double(field, wide)) return false;
  value = static_cast<float>(wide);
  return std::isfinite(value);
}

bool read_uint(std::string_view field, uint64_t max, uint64_t& value, int base) {
  if (field.empty() || field.front() == '-') return false;
  const char* end = field.data() + field.size();
  auto [ptr, ec] = std::from_chars(field.data(), end, value, base);
  return ec == std::errc() && ptr == end && value <= max;
}

bool read_int(std::string_view field, int64_t min, int64_t max, int64_t& value) {
  if (field.empty()) return false;
  const char* end = field.data() + field.size();
  auto [ptr, ec] = std::from_chars(field.data(), end, value, 10);
  return ec == std::errc() && ptr == end && value >= min && value <= max;
}

int hex_digit_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

HexCheck read_hex_check(const std::vector<uint8_t>& bytes, size_t from, size_t digits) {
  HexCheck h;
  const size_t end = from + digits;
  for (size_t j = from; j < end && j < bytes.size(); ++j) {
    const int digit = hex_digit_value(static_cast<char>(bytes[j]));
    if (digit < 0) {
      h.state = HexCheck::State::cut_short;
      h.cut_at = j;
      return h;
    }
    h.value = h.value << 4 | static_cast<uint32_t>(digit);
  }
  if (bytes.size() >= end) h.state = HexCheck::State::complete;
  return h;
}

}  // namespace brickyard::drivers
