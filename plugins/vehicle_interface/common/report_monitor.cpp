#include "report_monitor.hpp"

namespace brickyard::vehicle_interface {

ReportMonitor::ReportMonitor(int64_t timeout_ns, const std::array<uint32_t, kRaptorReports.size()>& moduli)
    : timeout_ns_(timeout_ns) {
  heard_ns_.fill(-1);
  for (size_t i = 0; i < moduli.size(); ++i) {
    has_counter_[i] = moduli[i] != 0;
    checkers_[i] = CounterChecker(moduli[i]);
  }
}

size_t ReportMonitor::slot(RaptorMessage report) {
  for (size_t i = 0; i < kRaptorReports.size(); ++i)
    if (kRaptorReports[i] == report) return i;
  return 0;  // never: every caller passes a report
}

std::string ReportMonitor::received(RaptorMessage report, int64_t now_ns, std::optional<uint32_t> counter) {
  const size_t i = slot(report);
  ++counts_[i].received;
  heard_ns_[i] = now_ns;
  silent_[i] = false;
  if (!has_counter_[i] || !counter) return "";
  uint32_t missed = 0;
  const CounterStep step = checkers_[i].check(*counter, &missed);
  if (step == CounterStep::skipped) {
    ++counts_[i].skips;
    counts_[i].missed += missed;
    return std::string(raptor_name(report)) + ": counter skipped " + std::to_string(missed) + " (" + std::to_string(*counter) + ")";
  }
  if (step == CounterStep::repeated) {
    ++counts_[i].repeats;
    return std::string(raptor_name(report)) + ": counter repeated " + std::to_string(*counter);
  }
  return "";
}

std::vector<RaptorMessage> ReportMonitor::check(int64_t now_ns) {
  if (start_ns_ < 0) start_ns_ = now_ns;
  std::vector<RaptorMessage> fell;
  for (size_t i = 0; i < kRaptorReports.size(); ++i) {
    const int64_t since = heard_ns_[i] >= 0 ? heard_ns_[i] : start_ns_;
    if (silent_[i] || now_ns - since <= timeout_ns_) continue;
    silent_[i] = true;
    ++counts_[i].silences;
    fell.push_back(kRaptorReports[i]);
  }
  return fell;
}

uint32_t ReportMonitor::silent_mask() const {
  uint32_t mask = 0;
  for (size_t i = 0; i < kRaptorReports.size(); ++i)
    if (silent_[i]) mask |= 1u << i;
  return mask;
}

uint64_t ReportMonitor::total_skips() const {
  uint64_t n = 0;
  for (const ReportCounts& c : counts_) n += c.skips;
  return n;
}

uint64_t ReportMonitor::total_silences() const {
  uint64_t n = 0;
  for (const ReportCounts& c : counts_) n += c.silences;
  return n;
}

std::optional<int64_t> ReportMonitor::last_heard(RaptorMessage report) const {
  const int64_t t = heard_ns_[slot(report)];
  return t >= 0 ? std::optional<int64_t>(t) : std::nullopt;
}

}  // namespace brickyard::vehicle_interface
