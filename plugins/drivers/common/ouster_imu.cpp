#include "ouster_imu.hpp"

#include <cmath>
#include <cstring>
#include <numbers>

namespace brickyard::drivers {
namespace {

std::uint64_t le64(const std::uint8_t* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

float le_float(const std::uint8_t* p) {
  const std::uint32_t bits = static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
                             static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void put_le64(std::uint8_t* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void put_le_float(std::uint8_t* p, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

}  // namespace

std::optional<OusterImuPacket> read_ouster_imu_packet(const std::uint8_t* data, std::size_t size) {
  if (size != kOusterImuPacketBytes) return std::nullopt;
  OusterImuPacket p;
  p.diagnostic_ns = le64(data);
  p.accel_ns = le64(data + 8);
  p.gyro_ns = le64(data + 16);
  for (int i = 0; i < 3; ++i) {
    p.accel_g[i] = le_float(data + 24 + 4 * i);
    p.gyro_dps[i] = le_float(data + 36 + 4 * i);
    if (!std::isfinite(p.accel_g[i]) || !std::isfinite(p.gyro_dps[i])) return std::nullopt;
  }
  return p;
}

std::array<std::uint8_t, kOusterImuPacketBytes> encode_ouster_imu_packet(const OusterImuPacket& p) {
  std::array<std::uint8_t, kOusterImuPacketBytes> out{};
  put_le64(out.data(), p.diagnostic_ns);
  put_le64(out.data() + 8, p.accel_ns);
  put_le64(out.data() + 16, p.gyro_ns);
  for (int i = 0; i < 3; ++i) {
    put_le_float(out.data() + 24 + 4 * i, p.accel_g[i]);
    put_le_float(out.data() + 36 + 4 * i, p.gyro_dps[i]);
  }
  return out;
}

OusterImuSample ouster_imu_in_sensor_frame(const OusterImuPacket& p, const std::array<double, 16>& t) {
  OusterImuSample s;
  s.time_ns = p.accel_ns;
  constexpr double kRadPerDeg = std::numbers::pi / 180;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) {
      s.accel[row] += t[4 * row + col] * p.accel_g[col] * kStandardGravity;
      s.gyro[row] += t[4 * row + col] * p.gyro_dps[col] * kRadPerDeg;
    }
  return s;
}

}  // namespace brickyard::drivers
