#pragma once
// A replay node's samples in the order they were recorded, each let go once the run's clock
// reaches its time, framework-free. M is what the node keeps of a sample (its message).
#include <cstdint>
#include <utility>
#include <vector>

namespace brickyard::replay {

template <class M> class SampleQueue {
 public:
  void push(std::int64_t stamp_ns, M m) { samples_.push_back({stamp_ns, std::move(m)}); }
  std::size_t size() const { return samples_.size(); }

  // Hands `send` each sample not sent yet whose time is at most `now_ns`, in order: the queue lets
  // go of it.
  template <class Send> void release(std::int64_t now_ns, Send&& send) {
    for (; next_ < samples_.size() && samples_[next_].stamp_ns <= now_ns; ++next_) send(std::move(samples_[next_].message));
  }
  std::size_t sent() const { return next_; }
  std::size_t left() const { return samples_.size() - next_; }

 private:
  struct Sample {
    std::int64_t stamp_ns;
    M message;
  };
  std::vector<Sample> samples_;
  std::size_t next_ = 0;
};

}  // namespace brickyard::replay
