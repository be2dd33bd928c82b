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

struct SourcePorts {
  Output<msgs::Blob> out;
};

PortBinding<SourcePorts> source_ports() {
  PortBinding<SourcePorts> b;
  b.output("out", &SourcePorts::out);
  return b;
}

struct SinkPorts {
  Input<msgs::Blob> in;
};

PortBinding<SinkPorts> sink_ports() {
  PortBinding<SinkPorts> b;
  b.input("in", &SinkPorts::in).steps();
  return b;
}

class BlobSource : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.blob_source", "1.0.0")
        .describe("Publishes Blob messages of size_bytes at rate_hz")
        .with_ports(source_ports())
        .parameters(source_bindings())
        .periodic("rate_hz");
  }
  void configure(Context& ctx) override {
    size_ = source_bindings().read(ctx.params()).size_bytes;
    io_ = source_ports().connect(ctx);
  }
  void step(Context& ctx) override {
    msgs::Blob b;
    b.header().stamp_ns(ctx.now_ns());
    b.header().seq(seq_++);
    b.data().assign(size_, static_cast<std::uint8_t>(seq_));
    io_.out.publish(std::move(b));
  }

 private:
  std::size_t size_ = 0;
  std::uint32_t seq_ = 0;
  SourcePorts io_;
};

class BlobSink : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.blob_sink", "1.0.0")
        .describe("Counts Blob messages and bytes; fails when fewer than min_count arrive")
        .with_ports(sink_ports())
        .parameters(sink_bindings());
  }
  void configure(Context& ctx) override {
    min_count_ = sink_bindings().read(ctx.params()).min_count;
    io_ = sink_ports().connect(ctx);
  }
  void step(Context&) override {
    for (const auto& b : io_.in.take()) {
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
  SinkPorts io_;
};

}  // namespace

BRICKYARD_PLUGINS(BlobSource, BlobSink)
