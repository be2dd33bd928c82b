#pragma once
// Reading the comma-separated text of OEM7 ASCII logs and NMEA 0183 sentences without exceptions
// or locales: every reader says whether the whole field was a valid value, so a decoder can
// refuse the message instead of guessing.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

// Splits `text` at commas into `fields` (views into `text`). With `quoted_strings` a field in double
// quotes is one field even if it holds commas (OEM7 ASCII strings); false if a quote is left open.
bool split_fields(std::string_view text, std::vector<std::string_view>& fields, bool quoted_strings);

// Finite decimal numbers ("-114.03827102462", "85.0", "1.5e-05"); no sign '+', no spaces, no "nan"/"inf".
bool read_double(std::string_view field, double& value);
bool read_float(std::string_view field, float& value);
// Integers in the given base (10, or 16 for OEM7 hex fields such as "02040008"), range-checked.
bool read_uint(std::string_view field, uint64_t max, uint64_t& value, int base = 10);
bool read_int(std::string_view field, int64_t min, int64_t max, int64_t& value);
// One hexadecimal digit's value, or -1.
int hex_digit_value(char c);

// A check value written as `digits` hex digits from `from` in a stream's buffered bytes (an OEM7
// ASCII log's CRC, an NMEA sentence's checksum, after their '*'): its value once every digit has
// come; where a byte is not a hex digit, that byte's index (the check value cut short).
struct HexCheck {
  enum class State { incomplete, complete, cut_short } state = State::incomplete;
  uint32_t value = 0;
  size_t cut_at = 0;  // cut_short: the index of the byte that is not a digit
};
HexCheck read_hex_check(const std::vector<uint8_t>& bytes, size_t from, size_t digits);

}  // namespace brickyard::drivers
