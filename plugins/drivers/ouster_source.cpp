#include "ouster_source.hpp"

#include "io/bounded_read.hpp"

#include <algorithm>
#include <stdexcept>

namespace brickyard::drivers {

namespace {
constexpr size_t kMaxCaptureBytes = size_t{4} << 30;
constexpr size_t kMaxPollBytes = size_t{16} << 20;  // per step: several frames of the largest sensor

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
    : s_(s), decoder_(s.metadata), table_(s.metadata), clock_(s.clock), pacer_(s.source.rate) {
  std::string error;
  if (s.source.kind == SourceSpec::Kind::pcap) {
    if (!io::read_regular_file(s.capture_path, kMaxCaptureBytes, capture_bytes_, error)) throw std::runtime_error(error);
    capture_.emplace(capture_bytes_);
    if (!capture_->ok()) throw std::runtime_error(s.capture_path + ": " + capture_->error());
    return;
  }
  device_ = open_source(s.source, error);
  if (!device_) throw std::runtime_error(error);
}

void OusterSource::feed_due_packets(int64_t now_ns) {
  const uint16_t port = s_.source.port ? s_.source.port : static_cast<uint16_t>(s_.metadata.udp_port_lidar);
  for (;;) {
    if (!pending_) pending_ = capture_->next();
    if (!pending_) {
      if (!capture_done_) decoder_.finish();  // the last rotation, complete or not
      capture_done_ = true;
      return;
    }
    if (!pacer_.due(static_cast<double>(pending_->time_ns) * 1e-9, now_ns)) return;
    if (pending_->destination_port == port) decoder_.feed(pending_->payload.data(), pending_->payload.size());
    pending_.reset();
  }
}

void OusterSource::feed_live_packets() {
  if (!device_error_.empty()) return;
  std::vector<std::vector<uint8_t>> packets;
  if (!device_->poll(packets, kMaxPollBytes)) device_error_ = device_->error();
  for (const auto& p : packets) decoder_.feed(p.data(), p.size());
  last_arrival_ns_ = -1;
  for (int64_t a : device_->arrivals_ns()) last_arrival_ns_ = std::max(last_arrival_ns_, a);
}

StampedCloud OusterSource::cloud_of(const OusterFrame& frame, int64_t receive_ns) {
  StampedCloud out;
  ouster_frame_to_cloud(frame, table_, out.cloud, s_.second_return);
  out.complete = frame.complete();
  out.stamp_ns = receive_ns;
  out.arrival_ns = last_arrival_ns_;
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
  if (capture_) feed_due_packets(now_ns);
  else feed_live_packets();
  std::vector<StampedCloud> out;
  while (auto frame = decoder_.next()) {
    out.push_back(cloud_of(*frame, now_ns));
    decoder_.recycle(std::move(*frame));
  }
  return out;
}

}  // namespace brickyard::drivers
