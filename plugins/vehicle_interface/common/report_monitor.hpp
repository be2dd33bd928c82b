#pragma once
// The drive-by-wire's reports watched: a report that stops arriving (nothing for timeout_s, from
// the first check on) is silent, said once per silence; a report whose rolling counter skips
// values (frames lost) or repeats the last one (a sender that is stuck) is counted, by report.
// docs/vehicle-interface.md, "Reports". Framework-free; times in ns of the run's clock.
#include "raptor_dbc.hpp"
#include "rolling_counter.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

struct ReportCounts {
  uint64_t received = 0;
  uint64_t skips = 0;          // frames whose counter skipped values
  uint64_t missed = 0;         // the values skipped: frames lost, as far as the counter tells
  uint64_t repeats = 0;        // frames whose counter repeated the last
  uint64_t silences = 0;
  uint64_t bad = 0;            // frames that could not be read (too short) or had values out of range
};

class ReportMonitor {
 public:
  // `moduli`: each report's counter modulus (0: it has none; RaptorDbc::counter_modulus).
  ReportMonitor(int64_t timeout_ns, const std::array<uint32_t, kRaptorReports.size()>& moduli);

  // A report arrived. Returns "" or what was wrong with its counter ("steering_report: counter
  // skipped 3 (12 after 8)", "... repeated 7").
  std::string received(RaptorMessage report, int64_t now_ns, std::optional<uint32_t> counter);
  void bad_frame(RaptorMessage report) { ++counts_[slot(report)].bad; }
  // The reports that fell silent since the last call (each once a silence).
  std::vector<RaptorMessage> check(int64_t now_ns);

  const ReportCounts& counts(RaptorMessage report) const { return counts_[slot(report)]; }
  uint32_t silent_mask() const;  // bit i: kRaptorReports[i] is silent now
  uint64_t total_skips() const;
  uint64_t total_silences() const;
  // The last time a report arrived (nullopt: never).
  std::optional<int64_t> last_heard(RaptorMessage report) const;

 private:
  static size_t slot(RaptorMessage report);

  int64_t timeout_ns_;
  int64_t start_ns_ = -1;
  std::array<CounterChecker, kRaptorReports.size()> checkers_;
  std::array<bool, kRaptorReports.size()> has_counter_{};
  std::array<int64_t, kRaptorReports.size()> heard_ns_;
  std::array<bool, kRaptorReports.size()> silent_{};
  std::array<ReportCounts, kRaptorReports.size()> counts_{};
};

}  // namespace brickyard::vehicle_interface
