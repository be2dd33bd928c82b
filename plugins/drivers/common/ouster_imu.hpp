#pragma once
// An Ouster sensor's IMU packets (its IMU port, 7503 by default, the LEGACY IMU profile),
// framework-free. Learned from Ouster's public sensor documentation and checked on the shipped
// captures (docs/drivers-formats.md, "Ouster IMU packets"): 48 bytes, little-endian: three
// timestamps in ns (the packet's diagnostic time, the accelerometer's read, the gyroscope's
// read), then the acceleration in g and the angular velocity in deg/s along the IMU's x, y, z.
// The sensor sends one every 10 ms. The accelerometer reads specific force: +1 g up at rest.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace brickyard::drivers {

constexpr std::size_t kOusterImuPacketBytes = 48;

struct OusterImuPacket {
  std::uint64_t diagnostic_ns = 0, accel_ns = 0, gyro_ns = 0;  // the sensor's clock
  std::array<float, 3> accel_g{}, gyro_dps{};
};

// Nothing when the packet is not 48 bytes or a reading is not finite.
std::optional<OusterImuPacket> read_ouster_imu_packet(const std::uint8_t* data, std::size_t size);
// The packet a sensor would send (the simulator's side, tests).
std::array<std::uint8_t, kOusterImuPacketBytes> encode_ouster_imu_packet(const OusterImuPacket& p);

// A packet in SI units and the sensor frame: specific force (m/s^2) and angular rate (rad/s)
// turned by the rotation of the metadata's imu_to_sensor_transform (row-major 4x4; its
// translation, the IMU's offset in the sensor, does not change either vector of a rigid body
// but for the lever arm's terms, left out: a few centimetres).
struct OusterImuSample {
  std::uint64_t time_ns = 0;  // the accelerometer's read
  std::array<double, 3> accel{}, gyro{};
};
OusterImuSample ouster_imu_in_sensor_frame(const OusterImuPacket& p, const std::array<double, 16>& imu_to_sensor);

}  // namespace brickyard::drivers
