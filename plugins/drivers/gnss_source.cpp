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
    while (auto f = stream_.next()) recorded_.push_back(*f);
    return;
  }
  std::string error;
  device_ = open_source(s.source, error);
  if (!device_) throw std::runtime_error(error);
}

StampedFix GnssSource::stamped(const GnssFixValues& f, int64_t receive_ns) {
  if (!s_.device_time || !f.device_time_ns) return {f, receive_ns};
  const int64_t stamp = clock_.stamp_ns(*f.device_time_ns, receive_ns);
  delays_s_.push_back(clock_.last_delay_s());
  return {f, stamp};
}

void GnssSource::replay_due(int64_t now_ns, std::vector<StampedFix>& out) {
  while (replayed_ < recorded_.size()) {
    const GnssFixValues& f = recorded_[replayed_];
    const double recorded_s = f.device_time_ns ? static_cast<double>(*f.device_time_ns) * 1e-9 : static_cast<double>(replayed_) * s_.replay_period_s;
    if (!pacer_.due(recorded_s, now_ns)) break;
    out.push_back(stamped(f, now_ns));
    ++replayed_;
  }
}

std::vector<StampedFix> GnssSource::poll(int64_t now_ns) {
  std::vector<StampedFix> out;
  if (!device_) {
    replay_due(now_ns, out);
    return out;
  }
  if (!device_error_.empty()) return out;
  std::vector<std::vector<uint8_t>> chunks;
  if (!device_->poll(chunks, kMaxPollBytes)) device_error_ = device_->error();
  for (const auto& c : chunks) {
    bytes_ += c.size();
    stream_.feed(c.data(), c.size());
  }
  while (auto f = stream_.next()) out.push_back(stamped(*f, now_ns));
  return out;
}

}  // namespace brickyard::drivers
