#pragma once
// Plugin-side (SDK-free): a sensor's UDP packets, live from its port or replayed from a packet
// capture (pcap) at the recorded pace, one payload at a time. What the Ouster drivers share (the
// lidar port's and the IMU port's nodes): each reads one port, so each its own feed.
#include "drivers/common/pcap_reader.hpp"
#include "drivers/common/replay_pacer.hpp"
#include "drivers/io/byte_source.hpp"
#include "drivers/io/reopening_device.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::drivers {

class PacketFeed {
 public:
  // A payload, and the kernel's receive time of its datagram (udp), else -1.
  using Take = std::function<void(const uint8_t* data, size_t size, int64_t arrival_ns)>;

  // `source`: udp:// (the port opened) or pcap:// (`capture_path`, the file found; its datagrams
  // to `capture_port` taken, the others skipped). Throws std::runtime_error naming the device or
  // the file when it cannot be opened or read.
  PacketFeed(const SourceSpec& source, const std::string& capture_path, uint16_t capture_port);

  // Hands `take` each payload that arrived (live), or whose recorded time is due by now_ns at the
  // source's rate (replay). Returns true once, the poll a capture ends in.
  bool poll(int64_t now_ns, const Take& take);

  // The kernel's receive time of the newest packet the last poll handed out (udp), else -1.
  int64_t last_arrival_ns() const { return last_arrival_ns_; }
  const PcapCounters* capture() const { return capture_ ? &capture_->counters() : nullptr; }
  const std::string& device_error() const { return device_ ? device_->error() : kNoError; }  // while a live device is failed
  const ReopeningDevice* device() const { return device_ ? &*device_ : nullptr; }
  bool reopens() const { return device_ && device_->reopens(); }
  bool replay_finished() const { return capture_ && capture_done_; }
  int fd() const { return device_ ? device_->fd() : -1; }  // a live device's, to wait on

 private:
  bool poll_capture(int64_t now_ns, const Take& take);
  void poll_device(int64_t now_ns, const Take& take);

  uint16_t capture_port_ = 0;
  std::optional<ReopeningDevice> device_;
  std::vector<uint8_t> capture_bytes_;
  std::optional<PcapReader> capture_;
  std::optional<UdpDatagram> pending_;  // read from the capture, not yet due
  bool capture_done_ = false;
  ReplayPacer pacer_;
  int64_t last_arrival_ns_ = -1;
  inline static const std::string kNoError;
};

}  // namespace brickyard::drivers
