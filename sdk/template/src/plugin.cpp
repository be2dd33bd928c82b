// example.my_plugin: the thin adapter between Brickyard and the algorithm in filter.hpp.
#include "filter.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <optional>

namespace {

using namespace brickyard;

// Each parameter is bound once to a member: its type, name and default are declared here and
// nowhere else; configure() reads them all with bindings().read().
struct Settings {
  double alpha = 0.5;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("alpha", &Settings::alpha).range(0.0, 1.0).doc("smoothing factor: 1 passes the input through");
  return b;
}

// Ports the same way: each is a typed member bound once to its name; the manifest declares them
// from the binding and configure() connects them all with ports().connect().
struct Ports {
  Input<msgs::Scalar> in;
  Output<msgs::Scalar> out;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("in", &Ports::in).doc("raw samples").steps();
  b.output("out", &Ports::out).doc("filtered samples, same stamps");
  return b;
}

class MyPlugin : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("example.my_plugin", "0.1.0")
        .describe("Low-pass filters a Scalar stream")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    filter_.emplace(bindings().read(ctx.params()).alpha);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& s : io_.in.take()) {
      msgs::Scalar m = *s;
      m.value(filter_->update(s->value()));
      io_.out.publish(std::move(m));
      ++count_;
    }
  }

  void deactivate(Context& ctx) override { ctx.metric("filtered", static_cast<double>(count_)); }

 private:
  std::optional<LowPass> filter_;
  Ports io_;
  long count_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(MyPlugin)
