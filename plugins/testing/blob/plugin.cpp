// testing.blob_source and testing.blob_sink: opaque payloads of a set size. One library, two
// plugins: the shape a library of related plugins takes.
#include <brickyard/msgs/Blob.h>
#include <brickyard/plugin.hpp>

namespace {

using namespace brickyard;

struct SourceSettings {
  std::size_t size_bytes = 0;
  double rate_hz = 10.0;
};

ParamBinding<SourceSettings> source_bindings() {
  ParamBinding<SourceSettings> b;
  b.bind_required("size_bytes", &SourceSettings::size_bytes).range(0, 256 << 20).in_unit("B");
  b.bind("rate_hz", &SourceSettings::rate_hz).in_unit("Hz").range(1e-3, 1e6);
  return b;
}

struct SinkSettings {
  std::int64_t min_count = 0;
};

ParamBinding<SinkSettings> sink_bindings() {
  ParamBinding<SinkSettings> b;
  b.bind("min_count", &SinkSettings::min_count).range(0, 1e9);
  return b;
}

class BlobSource : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.blob_source", "1.0.0")
        .describe("Publishes Blob messages of size_bytes at rate_hz")
        .output<msgs::Blob>("out")
        .parameters(source_bindings())
        .periodic("rate_hz");
  }
  void configure(Context& ctx) override {
    size_ = source_bindings().read(ctx.params()).size_bytes;
    out_ = ctx.output<msgs::Blob>("out");
  }
  void step(Context& ctx) override {
    msgs::Blob b;
    b.header().stamp_ns(ctx.now_ns());
    b.header().seq(seq_++);
    b.data().assign(size_, static_cast<std::uint8_t>(seq_));
    out_.publish(std::move(b));
  }

 private:
  std::size_t size_ = 0;
  std::uint32_t seq_ = 0;
  Output<msgs::Blob> out_;
};

class BlobSink : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.blob_sink", "1.0.0")
        .describe("Counts Blob messages and bytes; fails when fewer than min_count arrive")
        .input<msgs::Blob>("in")
        .parameters(sink_bindings())
        .on_input("in");
  }
  void configure(Context& ctx) override {
    min_count_ = sink_bindings().read(ctx.params()).min_count;
    in_ = ctx.input<msgs::Blob>("in");
  }
  void step(Context&) override {
    for (const auto& b : in_.take()) {
      ++count_;
      bytes_ += b->data().size();
    }
  }
  void deactivate(Context& ctx) override {
    ctx.metric("count", static_cast<double>(count_));
    ctx.metric("bytes", static_cast<double>(bytes_));
    if (count_ < min_count_) ctx.fail("received " + std::to_string(count_) + " blobs, expected at least " + std::to_string(min_count_));
  }

 private:
  std::int64_t min_count_ = 0, count_ = 0;
  std::uint64_t bytes_ = 0;
  Input<msgs::Blob> in_;
};

}  // namespace

BRICKYARD_PLUGINS(BlobSource, BlobSink)
