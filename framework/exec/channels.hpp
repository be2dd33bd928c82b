#pragma once
// Port endpoints: a bounded queue per input, a fan-out per output. Same-process readers get
// the publisher's object by pointer; the DDS writer serializes only for remote readers.
#include "exec/deferral.hpp"
#include "transport/dds.hpp"

#include <brickyard/context.hpp>

#include <algorithm>
#include <deque>
#include <functional>
#include <mutex>
#include <vector>

namespace eprosima::fastdds::dds { class TopicDataType; }

namespace brickyard::fw {

class InputQueue final : public detail::InputChannel {
 public:
  InputQueue(std::string name, std::string type, std::uint32_t depth, bool connected, bool phantom = false)
      : name_(std::move(name)), type_(std::move(type)), depth_(depth), connected_(connected), phantom_(phantom) {}

  const std::string& name() const { return name_; }
  const std::string& type_name() const override { return type_; }
  bool connected() const override { return connected_; }

  // An input of any type (Manifest::input_any): the type its wire carries, that type's IDL, and
  // what turns a sample of it into a SerializedSample (set by the executive).
  const std::string& wire_type() const override { return wire_type_.empty() ? type_ : wire_type_; }
  const char* wire_idl() const override { return wire_idl_.empty() ? nullptr : wire_idl_.c_str(); }
  void take_any(std::string type, std::string idl, std::function<std::shared_ptr<const void>(const void*)> serialize) {
    wire_type_ = std::move(type);
    wire_idl_ = std::move(idl);
    serialize_ = std::move(serialize);
  }

  // An input of another process's node in a lockstep run (exec/lockstep.hpp): it keeps nothing;
  // a sample's arrival only queues its phantom node's turn, as the real one's is queued there.
  bool phantom() const { return phantom_; }

  // Thread-safe; the oldest sample is dropped (and counted) when the queue is full.
  void push(std::shared_ptr<const void> s) {
    if (phantom_) {
      if (on_arrival) on_arrival(name_);
      return;
    }
    if (serialize_) s = serialize_(s.get());
    {
      std::lock_guard<std::mutex> l(m_);
      if (held_) {
        later_.push_back(std::move(s));
        return;
      }
      arrive(std::move(s));
    }
    if (on_arrival) on_arrival(name_);
  }
  // The sim clock, while a step of the owner runs beside later instants (a modelled latency):
  // samples published meanwhile wait, so the step reads what it would have at its instant, and
  // arrive in order when it is done; an input that wakes the node wakes it then, at that instant
  // (a step is done before the next one begins).
  void hold() {
    std::lock_guard<std::mutex> l(m_);
    held_ = true;
  }
  void release() {
    bool any;
    {
      std::lock_guard<std::mutex> l(m_);
      held_ = false;
      any = !later_.empty();
      for (auto& s : later_) arrive(std::move(s));
      later_.clear();
    }
    // An input that wakes its node: what came while the step was out wakes it now that it is done.
    if (any && on_arrival) on_arrival(name_);
  }
  std::vector<std::shared_ptr<const void>> take() override {
    std::lock_guard<std::mutex> l(m_);
    std::vector<std::shared_ptr<const void>> out(std::make_move_iterator(q_.begin()), std::make_move_iterator(q_.end()));
    q_.clear();
    return out;
  }
  std::shared_ptr<const void> latest() const override {
    std::lock_guard<std::mutex> l(m_);
    return last_;
  }
  std::uint64_t received() const { std::lock_guard<std::mutex> l(m_); return received_; }
  std::uint64_t dropped() const { std::lock_guard<std::mutex> l(m_); return dropped_; }

  // Staleness (the progress line, the summary): an input that has come at least three times is
  // stale when nothing has come for ten times its usual interval, and at least kStaleFloorNs — a
  // sensor gone quiet, a peer alive but silent. Its usual interval is learned (a running mean),
  // so a wire published once (a map) is never stale. Times on the run's clock: on the sim clock
  // reproducible, like the rest of the summary.
  static constexpr std::int64_t kStaleFloorNs = 500'000'000;
  struct Gaps {
    std::uint64_t received = 0;
    std::int64_t last_ns = 0, usual_ns = 0, max_gap_ns = 0;
    std::uint64_t stale_episodes = 0;  // gaps past the stale line, the one still open counted
    bool stale(std::int64_t now) const {
      return received >= 3 && now - last_ns > std::max<std::int64_t>(kStaleFloorNs, 10 * usual_ns);
    }
  };
  Gaps gaps() const { std::lock_guard<std::mutex> l(m_); return gaps_; }

  std::function<void(const std::string&)> on_arrival;  // set by the executive before the run
  std::function<std::int64_t()> clock;                  // the run's clock, for arrivals' times

 private:
  std::string name_, type_;
  std::uint32_t depth_;
  bool connected_, phantom_;
  std::string wire_type_, wire_idl_;
  std::function<std::shared_ptr<const void>(const void*)> serialize_;
  void arrive(std::shared_ptr<const void> s) {  // m_ held
    if (clock) {
      const std::int64_t t = clock();
      if (gaps_.received > 0) {
        const std::int64_t gap = t - gaps_.last_ns;
        if (gaps_.stale(t)) ++gaps_.stale_episodes;
        gaps_.max_gap_ns = std::max(gaps_.max_gap_ns, gap);
        gaps_.usual_ns = gaps_.received == 1 ? gap : gaps_.usual_ns + (gap - gaps_.usual_ns) / 8;
      }
      gaps_.last_ns = t;
      ++gaps_.received;
    }
    last_ = s;
    q_.push_back(std::move(s));
    ++received_;
    if (q_.size() > depth_) {
      q_.pop_front();
      ++dropped_;
    }
  }

  mutable std::mutex m_;
  bool held_ = false;
  std::vector<std::shared_ptr<const void>> later_;
  std::deque<std::shared_ptr<const void>> q_;
  std::shared_ptr<const void> last_;
  std::uint64_t received_ = 0, dropped_ = 0;
  Gaps gaps_;
};

class OutputPort final : public detail::OutputChannel {
 public:
  OutputPort(std::string name, std::string type) : name_(std::move(name)), type_(std::move(type)) {}
  const std::string& name() const { return name_; }
  const std::string& type_name() const override { return type_; }
  // An output of any type (Manifest::output_any): its readers' type, that type's IDL, and the
  // decoding of what the plugin publishes (a SerializedSample) into a sample of it.
  const std::string& wire_type() const override { return any_ ? wire_type_ : type_; }
  const char* wire_idl() const override { return wire_idl_.empty() ? nullptr : wire_idl_.c_str(); }
  void make_any(std::string type, std::string idl);

  void publish(std::shared_ptr<const void> s) override {
    if (!s) return;
    if (t_deferred) {  // stepped ahead of its turn: delivered at the turn
      t_deferred->emplace_back([this, s = std::move(s)]() mutable { publish(std::move(s)); });
      return;
    }
    if (any_) {  // the plugin's CDR, decoded once it is delivered
      if (wire_type_.empty()) return;  // it feeds nothing
      s = decode_any(*static_cast<const SerializedSample*>(s.get()));
    }
    if (t_publog) t_publog->push_back(index);  // a lockstep run's record of this step (exec/lockstep.hpp)
    ++published_;
    if (tap) tap(s.get());  // the recorder, before anyone downstream runs
    for (InputQueue* q : local) q->push(s);
    if (writer && writer->has_remote_readers() && !writer->write(s.get()) && write_failed) write_failed(name_);
  }
  std::uint64_t published() const { return published_; }

  std::vector<InputQueue*> local;
  DdsWriter* writer = nullptr;
  std::uint16_t index = 0;                          // its place among its node's outputs
  std::function<void(const std::string&)> write_failed;  // a lockstep run: a sample its peers need was not sent
  std::function<void(const void*)> tap;  // set by the executive when this port is recorded

 private:
  std::shared_ptr<const void> decode_any(const SerializedSample& s);
  bool any_ = false;
  std::string wire_type_, wire_idl_;
  std::shared_ptr<eprosima::fastdds::dds::TopicDataType> support_;
  std::string name_, type_;
  std::atomic<std::uint64_t> published_{0};
};

}  // namespace brickyard::fw
