#pragma once
// Assertions over a stream of (stamp, value) samples: count, rate, value range, ordering and
// an exact expected prefix. Framework-free: the assertion sink plugin is a thin adapter.
#include "math/fnv1a.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::testing {

struct StreamExpectations {
  std::int64_t min_count = 0;
  std::int64_t max_count = -1;          // -1: no limit
  std::optional<double> min_value, max_value;
  std::string ordering = "none";        // none | increasing | nondecreasing | decreasing
  std::optional<double> min_rate_hz, max_rate_hz;  // over sample stamps
  std::vector<double> expect_values;    // the first samples must equal these exactly
};

class StreamChecker {
 public:
  explicit StreamChecker(StreamExpectations e) : e_(std::move(e)) {}
  // Returns the first violation this sample causes, if any.
  std::optional<std::string> observe(std::int64_t stamp_ns, double value);
  // End-of-run checks (count, rate, expected prefix complete). Returns the violations.
  std::vector<std::string> finish() const;

  std::int64_t count() const { return count_; }
  double rate_hz() const;          // (count - 1) / (last stamp - first stamp); 0 if undefined
  double min() const { return min_; }
  double max() const { return max_; }
  double last() const { return last_value_; }
  // Hash of every stamp and value bit pattern: identical streams give identical digests.
  std::string digest() const;

 private:
  StreamExpectations e_;
  std::int64_t count_ = 0;
  std::int64_t first_stamp_ = 0, last_stamp_ = 0;
  double last_value_ = 0, min_ = 0, max_ = 0;
  math::Fnv1a hash_;
};

}  // namespace brickyard::testing
