#include "gnss_source.hpp"

#include "io/bounded_read.hpp"

#include <stdexcept>

namespace brickyard::drivers {

namespace {
constexpr size_t kMaxLogBytes = size_t{1} << 30;  // a recorded log: a day of 20 Hz BESTPOS is 30 MB
constexpr size_t kMaxPollBytes = size_t{1} << 20;  // per step: a step stays bounded
}  // namespace

GnssSource::GnssSource(const GnssSourceSettings& s) : s_(s), stream_(s.stream), clock_(s.clock), pacer_(s.source.rate) {
  if (s.source.kind == SourceSpec::Kind::file) {
    std::vector<uint8_t> bytes;
    std::string error;
    if (!io::read_regular_file(s.file_path, kMaxLogBytes, bytes, error)) throw std::runtime_error(error);
    bytes_ = bytes.size();
    stream_.feed(bytes.data(), bytes.size());
    stream_.finish();
    while (auto f = stream_.next()) fixes_.all.push_back(*f);
    while (auto v = stream_.next_imu()) imu_.all.push_back(*v);
    return;
  }
  device_.emplace(s.source, s.source.reopen_s);
}

int64_t GnssSource::stamp(std::optional<int64_t> device_ns, int64_t receive_ns) {
  if (!s_.device_time || !device_ns) return receive_ns;
  const int64_t stamped = clock_.stamp_ns(*device_ns, receive_ns);
  delays_s_.push_back(clock_.last_delay_s());
  return stamped;
}

void GnssSource::drain(int64_t receive_ns, int64_t arrival_ns, GnssPoll& out) {
  while (auto f = stream_.next()) out.fixes.push_back({*f, stamp(f->device_time_ns, receive_ns), arrival_ns});
  while (auto v = stream_.next_imu()) out.imu.push_back({*v, stamp(v->device_time_ns, receive_ns), arrival_ns});
}

void GnssSource::replay_due(int64_t now_ns, GnssPoll& out) {
  // Reports without a time go out one per replay_period_s, in order.
  auto recorded_s = [&](std::optional<int64_t> t, size_t at) {
    return t ? static_cast<double>(*t) * 1e-9 : static_cast<double>(at) * s_.replay_period_s;
  };
  for (; !fixes_.done(); ++fixes_.sent) {
    const GnssFixValues& f = fixes_.all[fixes_.sent];
    if (!pacer_.due(recorded_s(f.device_time_ns, fixes_.sent), now_ns)) break;
    out.fixes.push_back({f, stamp(f.device_time_ns, now_ns)});
  }
  for (; !imu_.done(); ++imu_.sent) {
    const ImuValues& v = imu_.all[imu_.sent];
    if (!pacer_.due(recorded_s(v.device_time_ns, imu_.sent), now_ns)) break;
    out.imu.push_back({v, stamp(v.device_time_ns, now_ns)});
  }
}

GnssPoll GnssSource::poll(int64_t now_ns) {
  GnssPoll out;
  if (!device_) {
    replay_due(now_ns, out);
    return out;
  }
  std::vector<std::vector<uint8_t>> chunks;
  device_->poll(now_ns, chunks, kMaxPollBytes);
  // Chunk by chunk: what a chunk completes is credited to its arrival.
  const std::vector<int64_t>& arrivals = device_->arrivals_ns();
  for (size_t i = 0; i < chunks.size(); ++i) {
    bytes_ += chunks[i].size();
    stream_.feed(chunks[i].data(), chunks[i].size());
    drain(now_ns, i < arrivals.size() ? arrivals[i] : -1, out);
  }
  return out;
}

}  // namespace brickyard::drivers
