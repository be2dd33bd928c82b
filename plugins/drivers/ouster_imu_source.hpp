#pragma once
// Plugin-side (SDK-free): an Ouster sensor's IMU, from its IMU port (UDP) or a packet capture
// replayed at its pace: each packet read (common/ouster_imu.hpp), turned from the IMU's axes into
// the sensor's (the metadata's imu_to_sensor_transform) and the vehicle's (the sensor's mount), and
// stamped by the time rule (common/device_clock.hpp) at its accelerometer's read.
#include "drivers/common/device_clock.hpp"
#include "drivers/common/ouster_imu.hpp"
#include "drivers/common/ouster_metadata.hpp"
#include "drivers/packet_feed.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::drivers {

struct OusterImuSourceSettings {
  SourceSpec source;
  std::string capture_path;  // pcap://: the capture found
  OusterMetadata metadata;
  Eigen::Matrix3d sensor_to_vehicle = Eigen::Matrix3d::Identity();  // the sensor's mount
  bool device_time = true;
  DeviceClockParams clock;
};

struct StampedOusterImu {
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // specific force, m/s^2, vehicle frame
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // rad/s, vehicle frame
  int64_t stamp_ns = 0;
  int64_t arrival_ns = -1;  // the kernel's receive time of its packet (udp), else -1
};

struct OusterImuCounters {
  uint64_t packets = 0;    // datagrams on the IMU port
  uint64_t samples = 0;    // read
  uint64_t malformed = 0;  // not 48 bytes, or a reading not finite: dropped
};

class OusterImuSource {
 public:
  // Opens the port or reads the capture; throws std::runtime_error naming it when it cannot.
  explicit OusterImuSource(const OusterImuSourceSettings& s);

  // The samples that arrived (or came due in the capture) by `now_ns`.
  std::vector<StampedOusterImu> poll(int64_t now_ns);

  const OusterImuCounters& counters() const { return counters_; }
  const PcapCounters* capture() const { return feed_.capture(); }
  const std::vector<double>& delays_s() const { return delays_s_; }
  const std::string& device_error() const { return feed_.device_error(); }
  const ReopeningDevice* device() const { return feed_.device(); }
  bool reopens() const { return feed_.reopens(); }
  bool replay_finished() const { return feed_.replay_finished(); }
  int fd() const { return feed_.fd(); }

 private:
  void read(const uint8_t* data, size_t size, int64_t now_ns, int64_t arrival_ns, std::vector<StampedOusterImu>& out);

  OusterImuSourceSettings s_;
  DeviceClock clock_;
  PacketFeed feed_;
  OusterImuCounters counters_;
  std::vector<double> delays_s_;
};

}  // namespace brickyard::drivers
