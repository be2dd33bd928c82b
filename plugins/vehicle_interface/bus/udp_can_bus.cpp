// udp://HOST:PORT + send_to: CAN frames in cannelloni's UDP datagrams, received on one port and
// sent to another, through the drivers' non-blocking UDP source and sink; or one way only (a
// receiver has no sink, a sender no source).
#include "can_bus.hpp"

#include "vehicle_interface/common/cannelloni.hpp"

namespace brickyard::vehicle_interface {

namespace {

class UdpCanBus final : public CanBus {
 public:
  UdpCanBus(std::unique_ptr<drivers::ByteSource> in, std::unique_ptr<drivers::ByteSink> out, std::string name)
      : in_(std::move(in)), out_(std::move(out)), name_(std::move(name)) {}

  bool poll(std::vector<CanFrame>& frames, size_t max_frames) override {
    if (!error_.empty()) return false;
    if (!in_) return true;  // a sender: nothing comes
    datagrams_.clear();
    // A datagram holds at most 1472 bytes of frames, over 100 classic frames: max_frames * 16
    // bytes reads at least max_frames frames' worth.
    const bool ok = in_->poll(datagrams_, max_frames * 16);
    for (const std::vector<uint8_t>& d : datagrams_) {
      const size_t before = frames.size();
      const bool had = counts_.datagrams_in > decoder_.counters().refused();
      const uint8_t expected = static_cast<uint8_t>(decoder_.last_sequence() + 1);
      ++counts_.datagrams_in;
      if (decoder_.decode(d.data(), d.size(), frames) != CannelloniRefusal::kNone) continue;
      // A gap in the sequence numbers: datagrams lost on the way (or reordered), as far as 8 bits tell.
      if (had) counts_.datagrams_lost += static_cast<uint8_t>(decoder_.last_sequence() - expected);
      counts_.frames_in += frames.size() - before;
    }
    counts_.datagrams_refused = decoder_.counters().refused();
    counts_.error_frames = decoder_.counters().error_frames;
    if (!ok) error_ = in_->error();
    return ok;
  }

  bool send(const std::vector<CanFrame>& frames) override {
    if (!error_.empty()) return false;
    if (frames.empty()) return true;
    if (!out_) {
      error_ = name_ + ": receives only";
      return false;
    }
    const CannelloniEncoding e = encode_cannelloni(frames, sequence_);
    if (!e.error.empty()) {  // a frame no bus carries: the interface never makes one
      counts_.frames_dropped += frames.size();
      return true;
    }
    const uint64_t dropped_before = out_->dropped();
    for (const std::vector<uint8_t>& d : e.datagrams) {
      if (!out_->send(d.data(), d.size())) {
        error_ = out_->error();
        return false;
      }
    }
    // The sink drops whole datagrams; a send that lost any is counted as all its frames lost (the
    // interface's sends are one datagram each: five frames are 46 bytes).
    if (out_->dropped() != dropped_before) counts_.frames_dropped += frames.size();
    else counts_.frames_out += frames.size();
    return true;
  }

  const std::string& error() const override { return error_; }
  const BusCounts& counts() const override { return counts_; }

 private:
  std::unique_ptr<drivers::ByteSource> in_;
  std::unique_ptr<drivers::ByteSink> out_;
  std::string name_;
  CannelloniDecoder decoder_;
  uint8_t sequence_ = 0;
  std::vector<std::vector<uint8_t>> datagrams_;
  BusCounts counts_;
  std::string error_;
};

}  // namespace

std::unique_ptr<CanBus> open_udp_bus(const BusSpec& spec, std::string& error) {
  std::unique_ptr<drivers::ByteSource> in = drivers::open_source(spec.listen, error);
  if (!in) return nullptr;
  std::unique_ptr<drivers::ByteSink> out = drivers::open_sink(spec.send_to, error);
  if (!out) return nullptr;
  return std::make_unique<UdpCanBus>(std::move(in), std::move(out), spec.text);
}

std::unique_ptr<CanBus> open_udp_receiver(const drivers::SourceSpec& listen, std::string& error) {
  std::unique_ptr<drivers::ByteSource> in = drivers::open_source(listen, error);
  if (!in) return nullptr;
  return std::make_unique<UdpCanBus>(std::move(in), nullptr, listen.text);
}

std::unique_ptr<CanBus> open_udp_sender(const drivers::SourceSpec& to, std::string& error) {
  std::unique_ptr<drivers::ByteSink> out = drivers::open_sink(to, error);
  if (!out) return nullptr;
  return std::make_unique<UdpCanBus>(nullptr, std::move(out), to.text);
}

}  // namespace brickyard::vehicle_interface
