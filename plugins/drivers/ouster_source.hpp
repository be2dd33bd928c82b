#pragma once
// Plugin-side (SDK-free): an Ouster sensor's frames as points, from its lidar port (UDP) or a
// packet capture replayed at its pace, each stamped by the time rule (common/device_clock.hpp) at
// the middle of its rotation (the stack takes a frame as measured at one time; the sweep's ends
// are half a rotation either side of it).
#include "drivers/common/device_clock.hpp"
#include "drivers/common/ouster_packets.hpp"
#include "drivers/common/ouster_xyz.hpp"
#include "drivers/packet_feed.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::drivers {

struct OusterSourceSettings {
  SourceSpec source;
  std::string capture_path;  // pcap://: the capture found
  OusterMetadata metadata;
  bool second_return = false;
  bool device_time = true;
  DeviceClockParams clock;
};

struct StampedCloud {
  OusterCloud cloud;
  int64_t stamp_ns = 0;
  bool complete = false;
  int64_t arrival_ns = -1;  // the kernel's receive time of the newest packet the poll fed (udp), else -1
  std::vector<float> time_offset_s;  // each point's time from stamp_ns (PointCloud.time_offset)
};

class OusterSource {
 public:
  // Opens the port or reads the capture; throws std::runtime_error naming it when it cannot.
  explicit OusterSource(const OusterSourceSettings& s);

  // The frames completed by `now_ns`, stamped.
  std::vector<StampedCloud> poll(int64_t now_ns);

  const OusterLidarDecoder& decoder() const { return decoder_; }
  const PcapCounters* capture() const { return feed_.capture(); }
  const std::vector<double>& delays_s() const { return delays_s_; }
  const std::string& device_error() const { return feed_.device_error(); }
  const ReopeningDevice* device() const { return feed_.device(); }
  bool reopens() const { return feed_.reopens(); }
  bool replay_finished() const { return feed_.replay_finished(); }
  int fd() const { return feed_.fd(); }  // a live device's, to wait on

 private:
  StampedCloud cloud_of(const OusterFrame& frame, int64_t receive_ns);

  OusterSourceSettings s_;
  OusterLidarDecoder decoder_;
  OusterXyzTable table_;
  DeviceClock clock_;
  PacketFeed feed_;
  std::vector<double> delays_s_;
};

}  // namespace brickyard::drivers
