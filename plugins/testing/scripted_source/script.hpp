#pragma once
// The value sequence of a scripted source: a list played in order (optionally looped), or an
// arithmetic ramp start, start + step, ... Framework-free.
#include <cstdint>
#include <optional>
#include <vector>

namespace brickyard::testing {

class ScalarScript {
 public:
  // count < 0: unlimited. With values, `loop` repeats them; without, the ramp is used.
  ScalarScript(std::vector<double> values, bool loop, double start, double step, std::int64_t count);
  // The next value, or nothing once the script is exhausted.
  std::optional<double> next();
  std::int64_t emitted() const { return emitted_; }

 private:
  std::vector<double> values_;
  bool loop_;
  double start_, step_;
  std::int64_t count_;
  std::int64_t emitted_ = 0;
};

}  // namespace brickyard::testing
