#include "nmea0183_sentences.hpp"

#include "text_fields.hpp"

#include <cmath>
#include <span>
#include <vector>

namespace brickyard::drivers {

namespace {

// Reads a sentence's fields in order; the first unreadable one marks the sentence bad. An empty
// field reads as an empty optional.
class SentenceCursor {
 public:
  explicit SentenceCursor(std::span<const std::string_view> fields) : fields_(fields) {}

  size_t remaining() const { return fields_.size() - at_; }
  bool ok() const { return ok_; }

  std::string_view text() { return at_ < fields_.size() ? fields_[at_++] : fail(); }

  std::optional<double> number() {
    std::string_view t = text();
    double v = 0;
    if (t.empty()) return std::nullopt;
    if (!read_double(t, v)) return bad<double>();
    return v;
  }

  std::optional<int> count(int max) {
    std::string_view t = text();
    uint64_t v = 0;
    if (t.empty()) return std::nullopt;
    if (!read_uint(t, static_cast<uint64_t>(max), v)) return bad<int>();
    return static_cast<int>(v);
  }

  // A single letter out of `allowed`, or 0 for an empty field.
  char letter(std::string_view allowed) {
    std::string_view t = text();
    if (t.empty()) return 0;
    if (t.size() != 1 || allowed.find(t[0]) == std::string_view::npos) return bad_letter();
    return t[0];
  }

  // A unit letter after a value ("M", "T", "N", "K"): the expected one, or empty.
  void unit(char expected) {
    std::string_view t = text();
    if (!t.empty() && !(t.size() == 1 && t[0] == expected)) ok_ = false;
  }

  // "ddmm.mmmm" (or "dddmm.mmmm") then its hemisphere letter; both empty before a fix.
  std::optional<double> angle(double max_degrees, char positive, char negative) {
    std::string_view value = text(), hemisphere = text();
    if (value.empty() && hemisphere.empty()) return std::nullopt;
    double v = 0;
    if (!read_double(value, v) || v < 0 || hemisphere.size() != 1) return bad<double>();
    double degrees = std::floor(v / 100.0);
    double minutes = v - degrees * 100.0;
    double angle = degrees + minutes / 60.0;
    if (minutes >= 60.0 || angle > max_degrees) return bad<double>();
    if (hemisphere[0] == positive) return angle;
    if (hemisphere[0] == negative) return -angle;
    return bad<double>();
  }

  // Plain degrees then a hemisphere letter ("16.9,W"): RMC's magnetic variation.
  std::optional<double> signed_degrees(double max_degrees, char positive, char negative) {
    std::string_view value = text(), hemisphere = text();
    if (value.empty() && hemisphere.empty()) return std::nullopt;
    double v = 0;
    if (!read_double(value, v) || v < 0 || v > max_degrees || hemisphere.size() != 1) return bad<double>();
    if (hemisphere[0] == positive) return v;
    if (hemisphere[0] == negative) return -v;
    return bad<double>();
  }

  // "hhmmss" or "hhmmss.ss".
  std::optional<NmeaTime> time() {
    std::string_view t = text();
    if (t.empty()) return std::nullopt;
    uint64_t h = 0, m = 0;
    double s = 0;
    if (t.size() < 6 || !read_uint(t.substr(0, 2), 23, h) || !read_uint(t.substr(2, 2), 59, m) ||
        !read_double(t.substr(4), s) || s < 0 || s >= 61.0)
      return bad<NmeaTime>();
    return NmeaTime{static_cast<int>(h), static_cast<int>(m), s};
  }

  // "ddmmyy".
  std::optional<NmeaDate> date() {
    std::string_view t = text();
    if (t.empty()) return std::nullopt;
    uint64_t d = 0, m = 0, y = 0;
    if (t.size() != 6 || !read_uint(t.substr(0, 2), 31, d) || !read_uint(t.substr(2, 2), 12, m) ||
        !read_uint(t.substr(4, 2), 99, y) || d == 0 || m == 0)
      return bad<NmeaDate>();
    int year = static_cast<int>(y) + (y < 80 ? 2000 : 1900);
    return NmeaDate{year, static_cast<int>(m), static_cast<int>(d)};
  }

 private:
  std::string_view fail() {
    ok_ = false;
    return {};
  }
  template <typename T>
  std::optional<T> bad() {
    ok_ = false;
    return std::nullopt;
  }
  char bad_letter() {
    ok_ = false;
    return 0;
  }
  std::span<const std::string_view> fields_;
  size_t at_ = 0;
  bool ok_ = true;
};

// "GGA,time,lat,N,lon,W,quality,satellites,hdop,altitude,M,undulation,M,age,station".
bool read_fields(SentenceCursor& f, NmeaGga& m) {
  m.utc = f.time();
  m.latitude_deg = f.angle(90, 'N', 'S');
  m.longitude_deg = f.angle(180, 'E', 'W');
  std::optional<int> quality = f.count(9);
  m.quality = quality.value_or(0);
  m.satellites_used = f.count(99);
  m.hdop = f.number();
  m.altitude_msl_m = f.number();
  f.unit('M');
  m.undulation_m = f.number();
  f.unit('M');
  m.differential_age_s = f.number();
  m.station_id = std::string(f.text());
  return f.ok() && quality.has_value();
}

// "RMC,time,status,lat,N,lon,W,knots,course,date,variation,E[,mode[,nav status]]".
bool read_fields(SentenceCursor& f, NmeaRmc& m) {
  m.utc = f.time();
  char status = f.letter("AV");
  m.valid = status == 'A';
  m.latitude_deg = f.angle(90, 'N', 'S');
  m.longitude_deg = f.angle(180, 'E', 'W');
  m.speed_knots = f.number();
  m.course_true_deg = f.number();
  m.date = f.date();
  m.magnetic_variation_deg = f.signed_degrees(180, 'E', 'W');
  if (f.remaining() > 0) m.mode = f.letter("ADEFMNRSP");
  if (f.remaining() > 0) m.nav_status = f.letter("SCUV");
  return f.ok() && status != 0;
}

// "VTG,course,T,course,M,knots,N,km/h,K[,mode]".
bool read_fields(SentenceCursor& f, NmeaVtg& m) {
  m.course_true_deg = f.number();
  f.unit('T');
  m.course_magnetic_deg = f.number();
  f.unit('M');
  m.speed_knots = f.number();
  f.unit('N');
  m.speed_kmh = f.number();
  f.unit('K');
  if (f.remaining() > 0) m.mode = f.letter("ADEFMNRSP");
  return f.ok();
}

// "GST,time,rms,semi-major,semi-minor,orientation,lat sigma,lon sigma,height sigma". A sigma is
// never negative; an orientation is within a turn.
bool read_fields(SentenceCursor& f, NmeaGst& m) {
  m.utc = f.time();
  m.range_rms_m = f.number();
  m.semi_major_m = f.number();
  m.semi_minor_m = f.number();
  m.orientation_deg = f.number();
  m.latitude_sigma_m = f.number();
  m.longitude_sigma_m = f.number();
  m.height_sigma_m = f.number();
  for (const auto& v : {m.range_rms_m, m.semi_major_m, m.semi_minor_m, m.latitude_sigma_m, m.longitude_sigma_m, m.height_sigma_m})
    if (v && !(*v >= 0)) return false;
  if (m.orientation_deg && !(*m.orientation_deg >= 0 && *m.orientation_deg <= 360)) return false;
  return f.ok() && f.remaining() == 0;
}

template <typename Message>
SentenceReadResult read_message(std::string_view talker, SentenceCursor& f, NmeaMessage& out) {
  Message m;
  m.talker = std::string(talker);
  if (!read_fields(f, m)) return SentenceReadResult::malformed;
  out = std::move(m);
  return SentenceReadResult::ok;
}

}  // namespace

SentenceReadResult read_sentence(std::string_view text, NmeaMessage& out) {
  std::vector<std::string_view> fields;
  split_fields(text, fields, false);
  std::string_view address = fields.front();
  // Approved sentences: a 2-letter talker and a 3-letter type; "P..." is a maker's own.
  if (address.size() != 5 || address[0] == 'P') return SentenceReadResult::unknown_sentence;
  std::string_view talker = address.substr(0, 2), type = address.substr(2);
  SentenceCursor cursor{std::span<const std::string_view>(fields).subspan(1)};
  if (type == "GGA") return read_message<NmeaGga>(talker, cursor, out);
  if (type == "RMC") return read_message<NmeaRmc>(talker, cursor, out);
  if (type == "VTG") return read_message<NmeaVtg>(talker, cursor, out);
  if (type == "GST") return read_message<NmeaGst>(talker, cursor, out);
  return SentenceReadResult::unknown_sentence;
}

}  // namespace brickyard::drivers
