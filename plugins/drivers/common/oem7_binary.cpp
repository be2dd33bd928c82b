#include "oem7_binary.hpp"

#include <bit>
#include <cmath>

namespace brickyard::drivers {

namespace {

// Little-endian fields, whatever the host's byte order; the caller has checked the size.
class LittleEndianReader {
 public:
  explicit LittleEndianReader(const uint8_t* bytes) : p_(bytes) {}
  uint8_t u8() { return p_[at_++]; }
  uint16_t u16() { return static_cast<uint16_t>(take(2)); }
  uint32_t u32() { return static_cast<uint32_t>(take(4)); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  float f32() { return std::bit_cast<float>(u32()); }
  double f64() { return std::bit_cast<double>(take(8)); }
  void skip(size_t n) { at_ += n; }

 private:
  uint64_t take(int n) {
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= static_cast<uint64_t>(p_[at_ + i]) << (8 * i);
    at_ += n;
    return v;
  }
  const uint8_t* p_;
  size_t at_ = 0;
};

class LittleEndianWriter {
 public:
  explicit LittleEndianWriter(std::vector<uint8_t>& bytes) : out_(bytes) {}
  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { put(v, 2); }
  void u32(uint32_t v) { put(v, 4); }
  void i32(int32_t v) { put(static_cast<uint32_t>(v), 4); }
  void f32(float v) { put(std::bit_cast<uint32_t>(v), 4); }
  void f64(double v) { put(std::bit_cast<uint64_t>(v), 8); }

 private:
  void put(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t>& out_;
};

// BESTPOS's station ID is a char[4], NUL-padded when shorter.
std::string read_char4(LittleEndianReader& r) {
  char bytes[4];
  for (char& c : bytes) c = static_cast<char>(r.u8());
  size_t length = 0;
  while (length < 4 && bytes[length] != '\0') ++length;
  return std::string(bytes, length);
}

void write_char4(const std::string& text, LittleEndianWriter& w) {
  for (size_t i = 0; i < 4; ++i) w.u8(i < text.size() ? static_cast<uint8_t>(text[i]) : 0);
}

}  // namespace

Oem7Header read_binary_header(const uint8_t* frame) {
  LittleEndianReader r(frame + 4);  // after the three sync bytes and the header length
  Oem7Header h;
  h.framing = Oem7Framing::binary;
  h.message_id = r.u16();
  r.skip(1);  // message type: checked by the framing
  h.port_address = r.u8();
  r.skip(2);  // message length: used by the framing
  h.sequence = r.u16();
  h.idle_percent = static_cast<float>(r.u8()) / 2.0f;
  h.time_status = static_cast<TimeStatus>(r.u8());
  h.week = r.u16();
  h.milliseconds = r.u32();
  h.receiver_status = r.u32();
  h.reserved = r.u16();
  h.receiver_sw_version = r.u16();
  return h;
}

Oem7Header read_binary_short_header(const uint8_t* frame) {
  LittleEndianReader r(frame + 4);  // after the three sync bytes and the body length
  Oem7Header h;
  h.framing = Oem7Framing::binary_short;
  h.message_id = r.u16();
  h.week = r.u16();
  h.milliseconds = r.u32();
  return h;
}

bool read_body(std::span<const uint8_t> body, BestPos& m) {
  if (body.size() < kBestPosBodyBytes) return false;
  LittleEndianReader r(body.data());
  m.solution_status = static_cast<SolutionStatus>(r.u32());
  m.position_type = static_cast<PositionType>(r.u32());
  m.latitude_deg = r.f64();
  m.longitude_deg = r.f64();
  m.height_msl_m = r.f64();
  m.undulation_m = r.f32();
  m.datum_id = r.u32();
  m.latitude_sigma_m = r.f32();
  m.longitude_sigma_m = r.f32();
  m.height_sigma_m = r.f32();
  m.base_station_id = read_char4(r);
  m.differential_age_s = r.f32();
  m.solution_age_s = r.f32();
  m.satellites_tracked = r.u8();
  m.satellites_in_solution = r.u8();
  m.satellites_l1_in_solution = r.u8();
  m.satellites_multi_in_solution = r.u8();
  m.reserved = r.u8();
  m.extended_solution_status = r.u8();
  m.galileo_beidou_signal_mask = r.u8();
  m.gps_glonass_signal_mask = r.u8();
  return true;
}

bool read_body(std::span<const uint8_t> body, BestVel& m) {
  if (body.size() < kBestVelBodyBytes) return false;
  LittleEndianReader r(body.data());
  m.solution_status = static_cast<SolutionStatus>(r.u32());
  m.velocity_type = static_cast<PositionType>(r.u32());
  m.latency_s = r.f32();
  m.differential_age_s = r.f32();
  m.horizontal_speed_mps = r.f64();
  m.track_over_ground_deg = r.f64();
  m.vertical_speed_mps = r.f64();
  m.reserved = r.f32();
  return true;
}

bool read_body(std::span<const uint8_t> body, InsPvaX& m) {
  if (body.size() < kInsPvaXBodyBytes) return false;
  LittleEndianReader r(body.data());
  m.ins_status = static_cast<InsStatus>(r.u32());
  m.position_type = static_cast<PositionType>(r.u32());
  m.latitude_deg = r.f64();
  m.longitude_deg = r.f64();
  m.height_msl_m = r.f64();
  m.undulation_m = r.f32();
  m.north_velocity_mps = r.f64();
  m.east_velocity_mps = r.f64();
  m.up_velocity_mps = r.f64();
  m.roll_deg = r.f64();
  m.pitch_deg = r.f64();
  m.azimuth_deg = r.f64();
  m.latitude_sigma_m = r.f32();
  m.longitude_sigma_m = r.f32();
  m.height_sigma_m = r.f32();
  m.north_velocity_sigma_mps = r.f32();
  m.east_velocity_sigma_mps = r.f32();
  m.up_velocity_sigma_mps = r.f32();
  m.roll_sigma_deg = r.f32();
  m.pitch_sigma_deg = r.f32();
  m.azimuth_sigma_deg = r.f32();
  m.extended_status = r.u32();
  m.seconds_since_update = r.u16();
  return true;
}

bool read_body(std::span<const uint8_t> body, RawImuSX& m) {
  if (body.size() < kRawImuSXBodyBytes) return false;
  LittleEndianReader r(body.data());
  m.imu_info = r.u8();
  m.imu_type = r.u8();
  m.gnss_week = r.u16();
  m.gnss_seconds_of_week = r.f64();
  m.imu_status = r.u32();
  m.accel_z_counts = r.i32();
  m.accel_minus_y_counts = r.i32();
  m.accel_x_counts = r.i32();
  m.gyro_z_counts = r.i32();
  m.gyro_minus_y_counts = r.i32();
  m.gyro_x_counts = r.i32();
  return true;
}

void write_binary_header(const Oem7Header& h, uint16_t message_id, uint16_t body_bytes, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u8(kOem7Sync0);
  w.u8(kOem7Sync1);
  w.u8(kOem7SyncLong);
  w.u8(static_cast<uint8_t>(kOem7HeaderBytes));
  w.u16(message_id);
  w.u8(0);  // message type: binary, original message
  w.u8(h.port_address);
  w.u16(body_bytes);
  w.u16(h.sequence);
  float idle = std::round(h.idle_percent * 2.0f);
  w.u8(static_cast<uint8_t>(idle < 0 ? 0 : idle > 200 ? 200 : idle));
  w.u8(static_cast<uint8_t>(h.time_status));
  w.u16(h.week);
  w.u32(h.milliseconds);
  w.u32(h.receiver_status);
  w.u16(h.reserved);
  w.u16(h.receiver_sw_version);
}

void write_binary_short_header(const Oem7Header& h, uint16_t message_id, uint8_t body_bytes, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u8(kOem7Sync0);
  w.u8(kOem7Sync1);
  w.u8(kOem7SyncShort);
  w.u8(body_bytes);
  w.u16(message_id);
  w.u16(h.week);
  w.u32(h.milliseconds);
}

void write_body(const BestPos& m, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u32(static_cast<uint32_t>(m.solution_status));
  w.u32(static_cast<uint32_t>(m.position_type));
  w.f64(m.latitude_deg);
  w.f64(m.longitude_deg);
  w.f64(m.height_msl_m);
  w.f32(m.undulation_m);
  w.u32(m.datum_id);
  w.f32(m.latitude_sigma_m);
  w.f32(m.longitude_sigma_m);
  w.f32(m.height_sigma_m);
  write_char4(m.base_station_id, w);
  w.f32(m.differential_age_s);
  w.f32(m.solution_age_s);
  w.u8(m.satellites_tracked);
  w.u8(m.satellites_in_solution);
  w.u8(m.satellites_l1_in_solution);
  w.u8(m.satellites_multi_in_solution);
  w.u8(m.reserved);
  w.u8(m.extended_solution_status);
  w.u8(m.galileo_beidou_signal_mask);
  w.u8(m.gps_glonass_signal_mask);
}

void write_body(const BestVel& m, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u32(static_cast<uint32_t>(m.solution_status));
  w.u32(static_cast<uint32_t>(m.velocity_type));
  w.f32(m.latency_s);
  w.f32(m.differential_age_s);
  w.f64(m.horizontal_speed_mps);
  w.f64(m.track_over_ground_deg);
  w.f64(m.vertical_speed_mps);
  w.f32(m.reserved);
}

void write_body(const InsPvaX& m, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u32(static_cast<uint32_t>(m.ins_status));
  w.u32(static_cast<uint32_t>(m.position_type));
  w.f64(m.latitude_deg);
  w.f64(m.longitude_deg);
  w.f64(m.height_msl_m);
  w.f32(m.undulation_m);
  for (double v : {m.north_velocity_mps, m.east_velocity_mps, m.up_velocity_mps, m.roll_deg, m.pitch_deg, m.azimuth_deg})
    w.f64(v);
  for (float v : {m.latitude_sigma_m, m.longitude_sigma_m, m.height_sigma_m, m.north_velocity_sigma_mps,
                  m.east_velocity_sigma_mps, m.up_velocity_sigma_mps, m.roll_sigma_deg, m.pitch_sigma_deg,
                  m.azimuth_sigma_deg})
    w.f32(v);
  w.u32(m.extended_status);
  w.u16(m.seconds_since_update);
}

void write_body(const RawImuSX& m, std::vector<uint8_t>& bytes) {
  LittleEndianWriter w(bytes);
  w.u8(m.imu_info);
  w.u8(m.imu_type);
  w.u16(m.gnss_week);
  w.f64(m.gnss_seconds_of_week);
  w.u32(m.imu_status);
  for (int32_t v : {m.accel_z_counts, m.accel_minus_y_counts, m.accel_x_counts, m.gyro_z_counts,
                    m.gyro_minus_y_counts, m.gyro_x_counts})
    w.i32(v);
}

}  // namespace brickyard::drivers
