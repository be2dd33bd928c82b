#include "ouster_imu.hpp"

#include "little_endian.hpp"

#include <cmath>
#include <numbers>

namespace brickyard::drivers {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

}  // namespace

std::optional<OusterImuPacket> read_ouster_imu_packet(const std::uint8_t* data, std::size_t size) {
  if (size != kOusterImuPacketBytes) return std::nullopt;
  OusterImuPacket p;
  p.diagnostic_ns = le::u64(data);
  p.accel_ns = le::u64(data + 8);
  p.gyro_ns = le::u64(data + 16);
  for (int i = 0; i < 3; ++i) {
    p.accel_g[i] = le::f32(data + 24 + 4 * i);
    p.gyro_dps[i] = le::f32(data + 36 + 4 * i);
    if (!std::isfinite(p.accel_g[i]) || !std::isfinite(p.gyro_dps[i])) return std::nullopt;
  }
  return p;
}

std::array<std::uint8_t, kOusterImuPacketBytes> encode_ouster_imu_packet(const OusterImuPacket& p) {
  std::array<std::uint8_t, kOusterImuPacketBytes> out{};
  le::put64(out.data(), p.diagnostic_ns);
  le::put64(out.data() + 8, p.accel_ns);
  le::put64(out.data() + 16, p.gyro_ns);
  for (int i = 0; i < 3; ++i) {
    le::put_f32(out.data() + 24 + 4 * i, p.accel_g[i]);
    le::put_f32(out.data() + 36 + 4 * i, p.gyro_dps[i]);
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
