#include "testing/assert_sink/stream_checker.hpp"

#include <cstdio>
#include <cstring>
#include <sstream>

namespace brickyard::testing {
namespace {
std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}
}  // namespace

std::optional<std::string> StreamChecker::observe(std::int64_t stamp_ns, double value) {
  std::optional<std::string> v;
  const std::string at = "sample " + std::to_string(count_) + " (value " + num(value) + "): ";
  if (count_ > 0) {
    const std::string& o = e_.ordering;
    bool bad = (o == "increasing" && !(value > last_value_)) || (o == "nondecreasing" && !(value >= last_value_)) ||
               (o == "decreasing" && !(value < last_value_));
    if (bad) v = at + "not " + o + " after " + num(last_value_);
  }
  if (!v && e_.min_value && value < *e_.min_value) v = at + "below min_value " + num(*e_.min_value);
  if (!v && e_.max_value && value > *e_.max_value) v = at + "above max_value " + num(*e_.max_value);
  if (!v && count_ < static_cast<std::int64_t>(e_.expect_values.size()) && value != e_.expect_values[count_])
    v = at + "expected " + num(e_.expect_values[count_]);
  if (!v && e_.max_count >= 0 && count_ + 1 > e_.max_count) v = at + "more than max_count " + std::to_string(e_.max_count);

  if (count_ == 0) {
    first_stamp_ = stamp_ns;
    min_ = max_ = value;
  }
  min_ = value < min_ ? value : min_;
  max_ = value > max_ ? value : max_;
  last_stamp_ = stamp_ns;
  last_value_ = value;
  ++count_;
  hash_.add(&stamp_ns, sizeof stamp_ns);
  hash_.add(&value, sizeof value);
  return v;
}

double StreamChecker::rate_hz() const {
  if (count_ < 2 || last_stamp_ <= first_stamp_) return 0;
  return static_cast<double>(count_ - 1) / ((last_stamp_ - first_stamp_) * 1e-9);
}

std::vector<std::string> StreamChecker::finish() const {
  std::vector<std::string> v;
  if (count_ < e_.min_count)
    v.push_back("received " + std::to_string(count_) + " samples, expected at least " + std::to_string(e_.min_count));
  if (count_ < static_cast<std::int64_t>(e_.expect_values.size()))
    v.push_back("received " + std::to_string(count_) + " samples, expect_values lists " +
                std::to_string(e_.expect_values.size()));
  double r = rate_hz();
  if (e_.min_rate_hz && r < *e_.min_rate_hz) v.push_back("rate " + num(r) + " Hz below min_rate_hz " + num(*e_.min_rate_hz));
  if (e_.max_rate_hz && r > *e_.max_rate_hz) v.push_back("rate " + num(r) + " Hz above max_rate_hz " + num(*e_.max_rate_hz));
  return v;
}

std::string StreamChecker::digest() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash_.value()));
  return buf;
}

}  // namespace brickyard::testing
