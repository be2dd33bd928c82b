#pragma once
// Rolling counters as the drive-by-wire's messages carry them: each frame of a message one more than
// the last, modulo the counter's modulus (RaptorDbc::counter_modulus). The sender's side numbers
// frames; the reader's side says whether a frame came in order, repeated the last (a sender that
// is stuck) or skipped some (frames lost). A modulus is at least 2. Framework-free.
#include <cstdint>
#include <optional>

namespace brickyard::vehicle_interface {

class CounterSender {
 public:
  explicit CounterSender(uint32_t modulus = 256) : modulus_(modulus < 2 ? 2 : modulus) {}
  uint32_t next() {  // 0, 1, ..., modulus - 1, 0, ...
    const uint32_t v = value_;
    value_ = (value_ + 1) % modulus_;
    return v;
  }

 private:
  uint32_t modulus_;
  uint32_t value_ = 0;
};

enum class CounterStep { first, in_order, repeated, skipped };

class CounterChecker {
 public:
  explicit CounterChecker(uint32_t modulus = 256) : modulus_(modulus < 2 ? 2 : modulus) {}
  // The frame's counter against the last one's. `missed` is how many values were skipped.
  CounterStep check(uint32_t counter, uint32_t* missed = nullptr) {
    const std::optional<uint32_t> last = last_;
    last_ = counter;
    if (missed) *missed = 0;
    if (!last) return CounterStep::first;
    const uint32_t step = (counter % modulus_ + modulus_ - *last % modulus_) % modulus_;
    if (step == 1) return CounterStep::in_order;
    if (step == 0) return CounterStep::repeated;
    if (missed) *missed = step - 1;
    return CounterStep::skipped;
  }
  void reset() { last_.reset(); }

 private:
  uint32_t modulus_;
  std::optional<uint32_t> last_;
};

}  // namespace brickyard::vehicle_interface
