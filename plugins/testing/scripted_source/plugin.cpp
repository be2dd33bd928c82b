// testing.scripted_source: publishes a scripted sequence of Scalar values at a fixed rate.
#include "testing/scripted_source/script.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <optional>
#include <random>

namespace {

using namespace brickyard;

struct Settings {
  double rate_hz = 10.0;
  std::vector<double> values;
  bool loop = false;
  double start = 0.0, step = 1.0;
  std::int64_t count = -1;
  double noise_std = 0.0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1e-3, 1e6).doc("publish rate");
  b.bind("values", &Settings::values).range(-1e6, 1e6).doc("values to play in order; empty: use the ramp");
  b.bind("loop", &Settings::loop).doc("repeat the values list");
  b.bind("start", &Settings::start).range(-1e6, 1e6).doc("first ramp value");
  b.bind("step", &Settings::step).range(-1e6, 1e6).doc("ramp increment per sample");
  b.bind("count", &Settings::count).range(-1, 1e9).doc("samples to publish; -1: unlimited");
  b.bind("noise_std", &Settings::noise_std).range(0, 1e6).doc("Gaussian noise added to each value, seeded by --seed");
  // The host's (Manifest::delivered_after): a source that models a sensor's latency.
  b.declare(ParamSpec::number("latency_s", 0).in_unit("s").range(0, 3600)
                .doc("sim clock: each sample, stamped when it is made, is delivered this long after; at most 1 / rate_hz"));
  return b;
}

struct Ports {
  Output<msgs::Scalar> out;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("out", &Ports::out).doc("one value per step");
  return b;
}

class ScriptedSource : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.scripted_source", "1.0.0")
        .describe("Publishes a scripted sequence of values: a list, or a ramp start + k*step")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz")
        .delivered_after("latency_s");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    script_.emplace(s.values, s.loop, s.start, s.step, s.count);
    io_ = ports().connect(ctx);
    noise_std_ = s.noise_std;
    rng_.seed(ctx.seed());
  }

  void step(Context& ctx) override {
    auto v = script_->next();
    if (!v) return;
    msgs::Scalar m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.value(noise_std_ > 0 ? *v + noise_std_ * normal_(rng_) : *v);
    io_.out.publish(std::move(m));
  }

  void deactivate(Context& ctx) override { ctx.metric("published", static_cast<double>(script_->emitted())); }

 private:
  std::optional<testing::ScalarScript> script_;
  Ports io_;
  std::uint32_t seq_ = 0;
  double noise_std_ = 0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
};

}  // namespace

BRICKYARD_PLUGINS(ScriptedSource)
