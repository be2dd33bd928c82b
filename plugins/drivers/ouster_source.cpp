#include "ouster_source.hpp"

#include <algorithm>
#include <stdexcept>

namespace brickyard::drivers {

namespace {

// The middle of the frame's arrived columns in the sensor's clock, ns; nothing when none arrived.
std::optional<int64_t> mid_time_ns(const OusterFrame& f) {
  uint64_t first = 0, last = 0;
  bool any = false;
  for (size_t c = 0; c < f.received.size(); ++c) {
    if (!f.received[c]) continue;
    const uint64_t t = f.timestamp_ns[c];
    if (!any || t < first) first = t;
    if (!any || t > last) last = t;
    any = true;
  }
  if (!any) return std::nullopt;
  return static_cast<int64_t>(first + (last - first) / 2);
}
// The last arrived column's time in the sensor's clock, ns; nothing when none arrived.
std::optional<int64_t> last_time_ns(const OusterFrame& f) {
  std::optional<int64_t> last;
  for (size_t c = 0; c < f.received.size(); ++c)
    if (f.received[c]) last = std::max(last.value_or(0), static_cast<int64_t>(f.timestamp_ns[c]));
  return last;
}
}  // namespace

OusterSource::OusterSource(const OusterSourceSettings& s)
    : s_(s), decoder_(s.metadata), table_(s.metadata), clock_(s.clock),
      feed_(s.source, s.capture_path, s.source.port ? s.source.port : static_cast<uint16_t>(s.metadata.udp_port_lidar)) {}

StampedCloud OusterSource::cloud_of(const OusterFrame& frame, int64_t receive_ns) {
  StampedCloud out;
  ouster_frame_to_cloud(frame, table_, out.cloud, s_.second_return);
  out.complete = frame.complete();
  out.stamp_ns = receive_ns;
  out.arrival_ns = feed_.last_arrival_ns();
  const std::optional<int64_t> measured = mid_time_ns(frame);
  if (s_.device_time && measured) {
    out.stamp_ns = clock_.stamp_ns(*measured, receive_ns);
    delays_s_.push_back(clock_.last_delay_s());
  }
  // Each point's time from the stamp: its column's, less the frame's middle (device time) or
  // last column (received: the frame is handed out as its last packet comes).
  if (const std::optional<int64_t> last = last_time_ns(frame); measured && last) {
    const int64_t zero = s_.device_time ? *measured : *last;
    out.time_offset_s.reserve(out.cloud.time_ns.size());
    for (uint64_t t : out.cloud.time_ns) out.time_offset_s.push_back(static_cast<float>(1e-9 * static_cast<double>(static_cast<int64_t>(t) - zero)));
  }
  return out;
}

std::vector<StampedCloud> OusterSource::poll(int64_t now_ns) {
  if (feed_.poll(now_ns, [this](const uint8_t* data, size_t size, int64_t) { decoder_.feed(data, size); }))
    decoder_.finish();  // the capture ended: the last rotation, complete or not
  std::vector<StampedCloud> out;
  while (auto frame = decoder_.next()) {
    out.push_back(cloud_of(*frame, now_ns));
    decoder_.recycle(std::move(*frame));
  }
  return out;
}

}  // namespace brickyard::drivers
