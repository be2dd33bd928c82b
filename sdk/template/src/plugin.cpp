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

class MyPlugin : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("example.my_plugin", "0.1.0")
        .describe("Low-pass filters a Scalar stream")
        .input<msgs::Scalar>("in", "raw samples")
        .output<msgs::Scalar>("out", "filtered samples, same stamps")
        .parameters(bindings())
        .on_input("in");
  }

  void configure(Context& ctx) override {
    filter_.emplace(bindings().read(ctx.params()).alpha);
    in_ = ctx.input<msgs::Scalar>("in");
    out_ = ctx.output<msgs::Scalar>("out");
  }

  void step(Context& ctx) override {
    for (const auto& s : in_.take()) {
      msgs::Scalar m = *s;
      m.value(filter_->update(s->value()));
      out_.publish(std::move(m));
      ++count_;
    }
  }

  void deactivate(Context& ctx) override { ctx.metric("filtered", static_cast<double>(count_)); }

 private:
  std::optional<LowPass> filter_;
  Input<msgs::Scalar> in_;
  Output<msgs::Scalar> out_;
  long count_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(MyPlugin)
