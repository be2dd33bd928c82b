#pragma once
// Plugin-side (SDK-free): a GNSS receiver's fixes and IMU samples, from a live device or a
// recorded log, each stamped by the time rule (common/device_clock.hpp: one clock, the
// receiver's, for both). Kept apart from the node so that plugin.cpp is the ports and parameters.
#include "drivers/common/device_clock.hpp"
#include "drivers/common/gnss_stream.hpp"
#include "drivers/common/replay_pacer.hpp"
#include "drivers/io/byte_source.hpp"
#include "drivers/io/reopening_device.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::drivers {

// arrival_ns: the kernel's receive time of the bytes that completed it (udp), else -1.
struct StampedFix {
  GnssFixValues fix;
  int64_t stamp_ns = 0;
  int64_t arrival_ns = -1;
};

struct StampedImu {
  ImuValues imu;
  int64_t stamp_ns = 0;
  int64_t arrival_ns = -1;
};

struct GnssPoll {
  std::vector<StampedFix> fixes;
  std::vector<StampedImu> imu;
};

struct GnssSourceSettings {
  SourceSpec source;
  std::string file_path;  // file://: the log found (Context::find_file)
  GnssStreamParams stream;
  bool device_time = true;    // false: stamped at receipt
  double replay_period_s = 0.05;  // file://: the pace of reports that carry no time
  DeviceClockParams clock;
};

class GnssSource {
 public:
  // Opens the device or reads the log; throws std::runtime_error naming it when it cannot.
  explicit GnssSource(const GnssSourceSettings& s);

  // What arrived (live) or fell due (replay) by `now_ns`, stamped.
  GnssPoll poll(int64_t now_ns);

  const GnssStream& stream() const { return stream_; }
  const std::vector<double>& delays_s() const { return delays_s_; }  // credited to each device-timed message
  const std::string& device_error() const { return device_ ? device_->error() : kNoError; }  // while a live device is failed
  const ReopeningDevice* device() const { return device_ ? &*device_ : nullptr; }
  bool reopens() const { return device_ && device_->reopens(); }
  uint64_t bytes() const { return bytes_; }
  int fd() const { return device_ ? device_->fd() : -1; }  // a live device's, to wait on
  bool replay_finished() const { return !device_ && fixes_.done() && imu_.done(); }

 private:
  // A recording's messages of one kind, in order, and how many went out.
  template <class T> struct Recorded {
    std::vector<T> all;
    size_t sent = 0;
    bool done() const { return sent == all.size(); }
  };

  int64_t stamp(std::optional<int64_t> device_ns, int64_t receive_ns);
  void drain(int64_t receive_ns, int64_t arrival_ns, GnssPoll& out);
  void replay_due(int64_t now_ns, GnssPoll& out);

  GnssSourceSettings s_;
  GnssStream stream_;
  DeviceClock clock_;
  std::optional<ReopeningDevice> device_;
  Recorded<GnssFixValues> fixes_;  // file://: every fix of the log
  Recorded<ImuValues> imu_;        // and every IMU sample
  ReplayPacer pacer_;
  std::vector<double> delays_s_;
  uint64_t bytes_ = 0;
  inline static const std::string kNoError;
};

}  // namespace brickyard::drivers
