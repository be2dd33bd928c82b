// GGA and RMC written as a receiver would, for the simulator and round-trip tests; numbers through
// std::to_chars so the output never depends on the process's locale.
#include "nmea0183.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace brickyard::drivers {

namespace {

constexpr long long kMinuteTicks = 10000000;  // 7 decimals of a minute of arc
constexpr long long kDegreeTicks = 60 * kMinuteTicks;

void append_fixed(std::string& out, double value, int decimals) {
  char text[64];
  auto result = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed, decimals);
  out.append(text, result.ptr);
}

void append_padded(std::string& out, long long value, int width) {
  std::string digits = std::to_string(value);
  if (static_cast<int>(digits.size()) < width) out.append(width - digits.size(), '0');
  out += digits;
}

void append_optional(std::string& out, const std::optional<double>& value, int decimals) {
  if (value) append_fixed(out, *value, decimals);
}

// "hhmmss.ss", or nothing.
void append_time(std::string& out, const std::optional<NmeaTime>& t) {
  if (!t) return;
  long long centiseconds = std::clamp(std::llround(t->seconds * 100.0), 0LL, 6099LL);
  append_padded(out, t->hours, 2);
  append_padded(out, t->minutes, 2);
  append_padded(out, centiseconds / 100, 2);
  out += '.';
  append_padded(out, centiseconds % 100, 2);
}

// "ddmm.mmmmmmm,N" (`degree_digits` 2) or "dddmm.mmmmmmm,E" (3), or ",". Rounded once, in whole
// ticks, so 59.99999999' can never print as "60.0000000".
void append_angle(std::string& out, const std::optional<double>& degrees, int degree_digits, char positive, char negative) {
  if (!degrees) {
    out += ',';
    return;
  }
  long long ticks = std::llround(std::fabs(*degrees) * static_cast<double>(kDegreeTicks));
  append_padded(out, ticks / kDegreeTicks, degree_digits);
  append_padded(out, ticks % kDegreeTicks / kMinuteTicks, 2);
  out += '.';
  append_padded(out, ticks % kMinuteTicks, 7);
  out += ',';
  out += *degrees < 0 ? negative : positive;
}

}  // namespace

std::string seal_nmea(const std::string& text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  uint8_t sum = nmea_checksum(text);
  std::string sentence = "$" + text + "*";
  sentence += kHex[sum >> 4];
  sentence += kHex[sum & 0x0F];
  sentence += "\r\n";
  return sentence;
}

std::string encode_gga(const NmeaGga& m) {
  std::string s = m.talker + "GGA,";
  append_time(s, m.utc);
  s += ',';
  append_angle(s, m.latitude_deg, 2, 'N', 'S');
  s += ',';
  append_angle(s, m.longitude_deg, 3, 'E', 'W');
  s += ',' + std::to_string(m.quality) + ',';
  if (m.satellites_used) append_padded(s, *m.satellites_used, 2);
  s += ',';
  append_optional(s, m.hdop, 1);
  s += ',';
  append_optional(s, m.altitude_msl_m, 3);
  s += m.altitude_msl_m ? ",M," : ",,";
  append_optional(s, m.undulation_m, 3);
  s += m.undulation_m ? ",M," : ",,";
  append_optional(s, m.differential_age_s, 1);
  s += ',' + m.station_id;
  return seal_nmea(s);
}

std::string encode_rmc(const NmeaRmc& m) {
  std::string s = m.talker + "RMC,";
  append_time(s, m.utc);
  s += m.valid ? ",A," : ",V,";
  append_angle(s, m.latitude_deg, 2, 'N', 'S');
  s += ',';
  append_angle(s, m.longitude_deg, 3, 'E', 'W');
  s += ',';
  append_optional(s, m.speed_knots, 3);
  s += ',';
  append_optional(s, m.course_true_deg, 3);
  s += ',';
  if (m.date) {
    append_padded(s, m.date->day, 2);
    append_padded(s, m.date->month, 2);
    append_padded(s, m.date->year % 100, 2);
  }
  s += ',';
  if (m.magnetic_variation_deg) {
    append_fixed(s, std::fabs(*m.magnetic_variation_deg), 1);
    s += *m.magnetic_variation_deg < 0 ? ",W" : ",E";
  } else {
    s += ',';
  }
  if (m.mode) s += std::string(",") + m.mode;
  if (m.mode && m.nav_status) s += std::string(",") + m.nav_status;
  return seal_nmea(s);
}

}  // namespace brickyard::drivers
