#include "ouster_imu_source.hpp"

namespace brickyard::drivers {

OusterImuSource::OusterImuSource(const OusterImuSourceSettings& s)
    : s_(s), clock_(s.clock),
      feed_(s.source, s.capture_path, s.source.port ? s.source.port : static_cast<uint16_t>(s.metadata.udp_port_imu)) {}

std::vector<StampedOusterImu> OusterImuSource::poll(int64_t now_ns) {
  std::vector<StampedOusterImu> out;
  feed_.poll(now_ns, [&](const uint8_t* data, size_t size, int64_t arrival_ns) { read(data, size, now_ns, arrival_ns, out); });
  return out;
}

void OusterImuSource::read(const uint8_t* data, size_t size, int64_t now_ns, int64_t arrival_ns, std::vector<StampedOusterImu>& out) {
  ++counters_.packets;
  const std::optional<OusterImuPacket> packet = read_ouster_imu_packet(data, size);
  if (!packet) {
    ++counters_.malformed;
    return;
  }
  ++counters_.samples;
  const OusterImuSample in_sensor = ouster_imu_in_sensor_frame(*packet, s_.metadata.imu_to_sensor);
  StampedOusterImu sample;
  sample.accel = s_.sensor_to_vehicle * Eigen::Vector3d(in_sensor.accel[0], in_sensor.accel[1], in_sensor.accel[2]);
  sample.gyro = s_.sensor_to_vehicle * Eigen::Vector3d(in_sensor.gyro[0], in_sensor.gyro[1], in_sensor.gyro[2]);
  sample.stamp_ns = now_ns;
  sample.arrival_ns = arrival_ns;
  if (s_.device_time) {
    sample.stamp_ns = clock_.stamp_ns(static_cast<int64_t>(in_sensor.time_ns), now_ns);
    delays_s_.push_back(clock_.last_delay_s());
  }
  out.push_back(sample);
}

}  // namespace brickyard::drivers
