// testing.scripted_source: publishes a scripted sequence of Scalar values at a fixed rate.
#include "scripted_source/script.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <optional>
#include <random>

namespace {

using namespace brickyard;

class ScriptedSource : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.scripted_source", "1.0.0")
        .describe("Publishes a scripted sequence of values: a list, or a ramp start + k*step")
        .output<msgs::Scalar>("out", "one value per step")
        .param(ParamSpec::number("rate_hz", 10.0).in_unit("Hz").range(1e-3, 1e6).doc("publish rate"))
        .param(ParamSpec::numbers("values", {}).doc("values to play in order; empty: use the ramp"))
        .param(ParamSpec::boolean("loop", false).doc("repeat the values list"))
        .param(ParamSpec::number("start", 0.0).doc("first ramp value"))
        .param(ParamSpec::number("step", 1.0).doc("ramp increment per sample"))
        .param(ParamSpec::integer("count", -1).at_least(-1).doc("samples to publish; -1: unlimited"))
        .param(ParamSpec::number("noise_std", 0.0).at_least(0).doc("Gaussian noise added to each value, seeded by --seed"))
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    script_.emplace(p.numbers("values"), p.boolean("loop"), p.number("start"), p.number("step"), p.integer("count"));
    out_ = ctx.output<msgs::Scalar>("out");
    noise_std_ = p.number("noise_std");
    rng_.seed(ctx.seed());
  }

  void step(Context& ctx) override {
    auto v = script_->next();
    if (!v) return;
    msgs::Scalar m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.value(noise_std_ > 0 ? *v + noise_std_ * normal_(rng_) : *v);
    out_.publish(std::move(m));
  }

  void deactivate(Context& ctx) override { ctx.metric("published", static_cast<double>(script_->emitted())); }

 private:
  std::optional<testing::ScalarScript> script_;
  Output<msgs::Scalar> out_;
  std::uint32_t seq_ = 0;
  double noise_std_ = 0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
};

}  // namespace

BRICKYARD_PLUGINS(ScriptedSource)
