#include "testing/scripted_source/script.hpp"

namespace brickyard::testing {

ScalarScript::ScalarScript(std::vector<double> values, bool loop, double start, double step, std::int64_t count)
    : values_(std::move(values)), loop_(loop), start_(start), step_(step), count_(count) {}

std::optional<double> ScalarScript::next() {
  if (count_ >= 0 && emitted_ >= count_) return std::nullopt;
  double v;
  if (values_.empty()) {
    v = start_ + step_ * static_cast<double>(emitted_);
  } else {
    std::size_t i = static_cast<std::size_t>(emitted_);
    if (i >= values_.size() && !loop_) return std::nullopt;
    v = values_[i % values_.size()];
  }
  ++emitted_;
  return v;
}

}  // namespace brickyard::testing
