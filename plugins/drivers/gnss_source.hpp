#pragma once
// Plugin-side (SDK): a GNSS driver's fixes, from a live device or a recorded log, each stamped by
// the time rule (common/device_clock.hpp). Kept apart from the node so that plugin.cpp is the
// ports and parameters only.
#include "drivers/common/device_clock.hpp"
#include "drivers/common/gnss_stream.hpp"
#include "drivers/common/replay_pacer.hpp"
#include "drivers/io/byte_source.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::drivers {

struct StampedFix {
  GnssFixValues fix;
  int64_t stamp_ns = 0;
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

  // The fixes that arrived (live) or fell due (replay) by `now_ns`, stamped.
  std::vector<StampedFix> poll(int64_t now_ns);

  const GnssStream& stream() const { return stream_; }
  const std::vector<double>& delays_s() const { return delays_s_; }  // credited to each device-timed fix
  const std::string& device_error() const { return device_error_; }   // set once a live device failed
  uint64_t bytes() const { return bytes_; }
  bool replay_finished() const { return !device_ && replayed_ == recorded_.size(); }

 private:
  StampedFix stamped(const GnssFixValues& f, int64_t receive_ns);
  void replay_due(int64_t now_ns, std::vector<StampedFix>& out);

  GnssSourceSettings s_;
  GnssStream stream_;
  DeviceClock clock_;
  std::unique_ptr<ByteSource> device_;
  std::vector<GnssFixValues> recorded_;  // file://: every fix of the log, in order
  size_t replayed_ = 0;
  ReplayPacer pacer_;
  std::vector<double> delays_s_;
  std::string device_error_;
  uint64_t bytes_ = 0;
};

}  // namespace brickyard::drivers
