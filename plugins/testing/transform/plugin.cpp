// testing.transform: y = gain * x + offset on every input sample; can be told to fail, so the
// executive's error handling is testable from a graph.
#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <stdexcept>

namespace {

using namespace brickyard;

class Transform : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.transform", "1.0.0")
        .describe("Affine transform of Scalar samples: y = gain * x + offset")
        .input<msgs::Scalar>("in", "samples to transform")
        .output<msgs::Scalar>("out", "transformed samples, same stamps")
        .param(ParamSpec::number("gain", 1.0))
        .param(ParamSpec::number("offset", 0.0))
        .param(ParamSpec::string("fault", "none").one_of({"none", "configure", "step"})
                   .doc("throw in configure, or in the step that handles sample number fault_at"))
        .param(ParamSpec::integer("fault_at", 0).at_least(0))
        .on_input("in");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    if (p.string("fault") == "configure") throw std::runtime_error("configured to fail in configure");
    gain_ = p.number("gain");
    offset_ = p.number("offset");
    fault_step_ = p.string("fault") == "step";
    fault_at_ = p.integer("fault_at");
    in_ = ctx.input<msgs::Scalar>("in");
    out_ = ctx.output<msgs::Scalar>("out");
  }

  void step(Context& ctx) override {
    for (const auto& s : in_.take()) {
      if (fault_step_ && handled_ == fault_at_) throw std::runtime_error("configured to fail at sample " + std::to_string(fault_at_));
      ++handled_;
      msgs::Scalar m = *s;
      m.value(gain_ * s->value() + offset_);
      out_.publish(std::move(m));
    }
  }

  void deactivate(Context& ctx) override { ctx.metric("handled", static_cast<double>(handled_)); }

 private:
  double gain_ = 1, offset_ = 0;
  bool fault_step_ = false;
  std::int64_t fault_at_ = 0, handled_ = 0;
  Input<msgs::Scalar> in_;
  Output<msgs::Scalar> out_;
};

}  // namespace

BRICKYARD_PLUGINS(Transform)
