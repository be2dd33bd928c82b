#include "packet_feed.hpp"

#include "io/bounded_read.hpp"

#include <algorithm>
#include <stdexcept>

namespace brickyard::drivers {

namespace {
constexpr size_t kMaxCaptureBytes = size_t{4} << 30;
constexpr size_t kMaxPollBytes = size_t{16} << 20;  // per step: several frames of the largest sensor
}  // namespace

PacketFeed::PacketFeed(const SourceSpec& source, const std::string& capture_path, uint16_t capture_port)
    : capture_port_(capture_port), pacer_(source.rate) {
  std::string error;
  if (source.kind == SourceSpec::Kind::pcap) {
    if (!io::read_regular_file(capture_path, kMaxCaptureBytes, capture_bytes_, error)) throw std::runtime_error(error);
    capture_.emplace(capture_bytes_);
    if (!capture_->ok()) throw std::runtime_error(capture_path + ": " + capture_->error());
    return;
  }
  device_.emplace(source, source.reopen_s);
}

bool PacketFeed::poll(int64_t now_ns, const Take& take) {
  if (capture_) return poll_capture(now_ns, take);
  poll_device(now_ns, take);
  return false;
}

bool PacketFeed::poll_capture(int64_t now_ns, const Take& take) {
  for (;;) {
    if (!pending_) pending_ = capture_->next();
    if (!pending_) {
      const bool ends_now = !capture_done_;
      capture_done_ = true;
      return ends_now;
    }
    if (!pacer_.due(static_cast<double>(pending_->time_ns) * 1e-9, now_ns)) return false;
    if (pending_->destination_port == capture_port_) take(pending_->payload.data(), pending_->payload.size(), -1);
    pending_.reset();
  }
}

void PacketFeed::poll_device(int64_t now_ns, const Take& take) {
  std::vector<std::vector<uint8_t>> packets;
  device_->poll(now_ns, packets, kMaxPollBytes);
  const std::vector<int64_t>& arrivals = device_->arrivals_ns();
  last_arrival_ns_ = -1;
  for (size_t i = 0; i < packets.size(); ++i) {
    const int64_t arrival = arrivals.size() == packets.size() ? arrivals[i] : -1;
    take(packets[i].data(), packets[i].size(), arrival);
  }
  for (int64_t a : arrivals) last_arrival_ns_ = std::max(last_arrival_ns_, a);
}

}  // namespace brickyard::drivers
