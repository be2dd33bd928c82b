// testing.transform: y = gain * x + offset on every input sample; can be told to fail, so the
// executive's error handling is testable from a graph.
#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <stdexcept>

namespace {

using namespace brickyard;

enum class Fault { none, configure, step };

struct Settings {
  double gain = 1.0, offset = 0.0;
  Fault fault = Fault::none;
  std::int64_t fault_at = 0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("gain", &Settings::gain).range(-1e6, 1e6);
  b.bind("offset", &Settings::offset).range(-1e6, 1e6);
  b.bind_choice("fault", {{"none", Fault::none}, {"configure", Fault::configure}, {"step", Fault::step}}, &Settings::fault)
      .doc("throw in configure, or in the step that handles sample number fault_at");
  b.bind("fault_at", &Settings::fault_at).range(0, 1e9);
  // The host's (Manifest::delivered_after): a computation that takes time.
  b.declare(ParamSpec::number("latency_s", 0).in_unit("s").range(0, 10)
                .doc("what a step publishes is delivered this long after it (sim clock; 0: at once)"));
  return b;
}

struct Ports {
  Input<msgs::Scalar> in;
  Output<msgs::Scalar> out;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("in", &Ports::in).doc("samples to transform").steps();
  b.output("out", &Ports::out).doc("transformed samples, same stamps");
  return b;
}

class Transform : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.transform", "1.0.0")
        .describe("Affine transform of Scalar samples: y = gain * x + offset")
        .with_ports(ports())
        .parameters(bindings())
        .delivered_after("latency_s");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    if (s.fault == Fault::configure) throw std::runtime_error("configured to fail in configure");
    gain_ = s.gain;
    offset_ = s.offset;
    fault_step_ = s.fault == Fault::step;
    fault_at_ = s.fault_at;
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& s : io_.in.take()) {
      if (fault_step_ && handled_ == fault_at_) throw std::runtime_error("configured to fail at sample " + std::to_string(fault_at_));
      ++handled_;
      msgs::Scalar m = *s;
      m.value(gain_ * s->value() + offset_);
      io_.out.publish(std::move(m));
    }
  }

  void deactivate(Context& ctx) override { ctx.metric("handled", static_cast<double>(handled_)); }

 private:
  double gain_ = 1, offset_ = 0;
  bool fault_step_ = false;
  std::int64_t fault_at_ = 0, handled_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Transform)
