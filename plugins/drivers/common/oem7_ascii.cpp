#include "oem7_ascii.hpp"

#include "oem7_enum_names.hpp"
#include "text_fields.hpp"

#include <cmath>
#include <optional>
#include <span>
#include <vector>

namespace brickyard::drivers {

namespace {

constexpr uint32_t kMillisecondsPerWeek = 604800u * 1000u;

// Reads a log's fields in order; the first unreadable one marks the whole log bad.
class FieldCursor {
 public:
  explicit FieldCursor(std::span<const std::string_view> fields) : fields_(fields) {}

  std::string_view text() { return at_ < fields_.size() ? fields_[at_++] : fail(); }
  double f64() {
    double v = 0;
    if (!read_double(text(), v)) ok_ = false;
    return v;
  }
  float f32() {
    float v = 0;
    if (!read_float(text(), v)) ok_ = false;
    return v;
  }
  uint64_t unsigned_value(uint64_t max, int base = 10) {
    uint64_t v = 0;
    if (!read_uint(text(), max, v, base)) ok_ = false;
    return v;
  }
  int32_t i32() {
    int64_t v = 0;
    if (!read_int(text(), INT32_MIN, INT32_MAX, v)) ok_ = false;
    return static_cast<int32_t>(v);
  }
  template <typename Enum>
  Enum name(std::optional<Enum> (*from_name)(std::string_view)) {
    std::optional<Enum> v = from_name(text());
    if (!v) ok_ = false;
    return v.value_or(Enum{});
  }
  // GPS seconds of week as printed ("450849.500") to whole milliseconds.
  uint32_t milliseconds_of_week() {
    double s = f64();
    double ms = std::round(s * 1000.0);
    if (!(ms >= 0 && ms < kMillisecondsPerWeek)) ok_ = false;
    return ok_ ? static_cast<uint32_t>(ms) : 0;
  }
  // A double-quoted string field (`"TSTR"`, `""`) of at most `max_size` characters.
  std::string quoted(size_t max_size) {
    std::string_view f = text();
    if (f.size() < 2 || f.front() != '"' || f.back() != '"' || f.size() - 2 > max_size) ok_ = false;
    return ok_ ? std::string(f.substr(1, f.size() - 2)) : std::string();
  }
  bool ok() const { return ok_; }

 private:
  std::string_view fail() {
    ok_ = false;
    return {};
  }
  std::span<const std::string_view> fields_;
  size_t at_ = 0;
  bool ok_ = true;
};

// "#NAMEA,port,sequence,idle,time status,week,seconds,receiver status,reserved,sw version".
bool read_header(FieldCursor& f, Oem7Header& h) {
  h.framing = Oem7Framing::ascii;
  h.port = std::string(f.text());
  h.sequence = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  h.idle_percent = f.f32();
  h.time_status = f.name(time_status_from_name);
  h.week = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  h.milliseconds = f.milliseconds_of_week();
  h.receiver_status = static_cast<uint32_t>(f.unsigned_value(UINT32_MAX, 16));
  h.reserved = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX, 16));
  h.receiver_sw_version = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  return f.ok() && !h.port.empty();
}

// "%NAMEA,week,seconds".
bool read_short_header(FieldCursor& f, Oem7Header& h) {
  h.framing = Oem7Framing::ascii_short;
  h.week = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  h.milliseconds = f.milliseconds_of_week();
  return f.ok();
}

bool read_fields(FieldCursor& f, BestPos& m) {
  m.solution_status = f.name(solution_status_from_name);
  m.position_type = f.name(position_type_from_name);
  m.latitude_deg = f.f64();
  m.longitude_deg = f.f64();
  m.height_msl_m = f.f64();
  m.undulation_m = f.f32();
  m.datum_id = f.name(datum_from_name);
  m.latitude_sigma_m = f.f32();
  m.longitude_sigma_m = f.f32();
  m.height_sigma_m = f.f32();
  m.base_station_id = f.quoted(4);
  m.differential_age_s = f.f32();
  m.solution_age_s = f.f32();
  m.satellites_tracked = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX));
  m.satellites_in_solution = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX));
  m.satellites_l1_in_solution = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX));
  m.satellites_multi_in_solution = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX));
  m.reserved = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX, 16));
  m.extended_solution_status = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX, 16));
  m.galileo_beidou_signal_mask = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX, 16));
  m.gps_glonass_signal_mask = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX, 16));
  return f.ok();
}

bool read_fields(FieldCursor& f, BestVel& m) {
  m.solution_status = f.name(solution_status_from_name);
  m.velocity_type = f.name(position_type_from_name);
  m.latency_s = f.f32();
  m.differential_age_s = f.f32();
  m.horizontal_speed_mps = f.f64();
  m.track_over_ground_deg = f.f64();
  m.vertical_speed_mps = f.f64();
  m.reserved = f.f32();
  return f.ok();
}

bool read_fields(FieldCursor& f, InsPvaX& m) {
  m.ins_status = f.name(ins_status_from_name);
  m.position_type = f.name(position_type_from_name);
  m.latitude_deg = f.f64();
  m.longitude_deg = f.f64();
  m.height_msl_m = f.f64();
  m.undulation_m = f.f32();
  for (double* v : {&m.north_velocity_mps, &m.east_velocity_mps, &m.up_velocity_mps, &m.roll_deg, &m.pitch_deg, &m.azimuth_deg})
    *v = f.f64();
  for (float* v : {&m.latitude_sigma_m, &m.longitude_sigma_m, &m.height_sigma_m, &m.north_velocity_sigma_mps,
                   &m.east_velocity_sigma_mps, &m.up_velocity_sigma_mps, &m.roll_sigma_deg, &m.pitch_sigma_deg,
                   &m.azimuth_sigma_deg})
    *v = f.f32();
  m.extended_status = static_cast<uint32_t>(f.unsigned_value(UINT32_MAX, 16));
  m.seconds_since_update = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  return f.ok();
}

bool read_fields(FieldCursor& f, RawImuSX& m) {
  m.imu_info = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX, 16));
  m.imu_type = static_cast<uint8_t>(f.unsigned_value(UINT8_MAX));
  m.gnss_week = static_cast<uint16_t>(f.unsigned_value(UINT16_MAX));
  m.gnss_seconds_of_week = f.f64();
  m.imu_status = static_cast<uint32_t>(f.unsigned_value(UINT32_MAX, 16));
  for (int32_t* v : {&m.accel_z_counts, &m.accel_minus_y_counts, &m.accel_x_counts, &m.gyro_z_counts,
                     &m.gyro_minus_y_counts, &m.gyro_x_counts})
    *v = f.i32();
  return f.ok();
}

// The message a log's name announces ("BESTPOSA"), default-constructed; nothing for other logs.
std::optional<Oem7Message> message_named(std::string_view name) {
  if (name == "BESTPOSA") return BestPos{};
  if (name == "BESTVELA") return BestVel{};
  if (name == "INSPVAXA") return InsPvaX{};
  if (name == "RAWIMUSXA") return RawImuSX{};
  return std::nullopt;
}

uint16_t message_id_of(const Oem7Message& m) {
  constexpr uint16_t ids[] = {kBestPosId, kBestVelId, kInsPvaXId, kRawImuSXId};
  return ids[m.index()];
}

}  // namespace

AsciiReadResult read_ascii_log(std::string_view text, bool short_header, Oem7Message& out) {
  size_t semicolon = text.find(';');
  if (semicolon == std::string_view::npos) return AsciiReadResult::malformed;
  std::vector<std::string_view> header_fields, body_fields;
  split_fields(text.substr(0, semicolon), header_fields, false);
  std::optional<Oem7Message> message = message_named(header_fields.front());
  if (!message) return AsciiReadResult::unknown_message;
  if (!split_fields(text.substr(semicolon + 1), body_fields, true)) return AsciiReadResult::malformed;

  FieldCursor header_cursor{std::span<const std::string_view>(header_fields).subspan(1)};
  FieldCursor body_cursor(body_fields);
  bool ok = std::visit(
      [&](auto& m) {
        bool header_ok = short_header ? read_short_header(header_cursor, m.header) : read_header(header_cursor, m.header);
        return header_ok && read_fields(body_cursor, m);
      },
      *message);
  if (!ok) return AsciiReadResult::malformed;
  std::visit([&](auto& m) { m.header.message_id = message_id_of(*message); }, *message);
  out = std::move(*message);
  return AsciiReadResult::ok;
}

}  // namespace brickyard::drivers
