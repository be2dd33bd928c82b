// testing.assert_sink: checks a Scalar stream and fails the run (exit 1) on any violation.
#include "assert_sink/stream_checker.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <cmath>
#include <limits>
#include <optional>

namespace {

using namespace brickyard;

std::optional<double> opt(const Params& p, const char* name) {
  double v = p.number(name);
  return std::isnan(v) ? std::nullopt : std::optional<double>(v);
}

class AssertSink : public Plugin {
 public:
  static Manifest manifest() {
    const double off = std::numeric_limits<double>::quiet_NaN();
    return Manifest("testing.assert_sink", "1.0.0")
        .describe("Asserts count, rate, value range, ordering and exact values of a Scalar stream; fails the run when violated")
        .input<msgs::Scalar>("in", "the stream under test", true, 1024)
        .param(ParamSpec::integer("min_count", 0).at_least(0))
        .param(ParamSpec::integer("max_count", -1).at_least(-1).doc("-1: no limit"))
        .param(ParamSpec::number("min_value", off).doc("NaN: no check"))
        .param(ParamSpec::number("max_value", off).doc("NaN: no check"))
        .param(ParamSpec::string("ordering", "none").one_of({"none", "increasing", "nondecreasing", "decreasing"}))
        .param(ParamSpec::number("min_rate_hz", off).in_unit("Hz").doc("over sample stamps; NaN: no check"))
        .param(ParamSpec::number("max_rate_hz", off).in_unit("Hz").doc("over sample stamps; NaN: no check"))
        .param(ParamSpec::numbers("expect_values", {}).doc("the first samples must equal these"))
        .param(ParamSpec::integer("finish_after", 0).at_least(0).doc("end the run successfully after this many samples; 0: never"))
        .on_input("in");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    testing::StreamExpectations e;
    e.min_count = p.integer("min_count");
    e.max_count = p.integer("max_count");
    e.min_value = opt(p, "min_value");
    e.max_value = opt(p, "max_value");
    e.ordering = p.string("ordering");
    e.min_rate_hz = opt(p, "min_rate_hz");
    e.max_rate_hz = opt(p, "max_rate_hz");
    e.expect_values = p.numbers("expect_values");
    finish_after_ = p.integer("finish_after");
    checker_.emplace(std::move(e));
    in_ = ctx.input<msgs::Scalar>("in");
  }

  void step(Context& ctx) override {
    for (const auto& s : in_.take()) {
      if (auto v = checker_->observe(s->header().stamp_ns(), s->value())) {
        violations_.push_back(*v);
        ctx.fail(*v);
      }
      if (finish_after_ > 0 && checker_->count() == finish_after_) ctx.finish("received " + std::to_string(finish_after_) + " samples");
    }
  }

  void deactivate(Context& ctx) override {
    for (const auto& s : in_.take()) checker_->observe(s->header().stamp_ns(), s->value());
    auto end = checker_->finish();
    ctx.metric("count", static_cast<double>(checker_->count()));
    ctx.metric("rate_hz", checker_->rate_hz());
    ctx.metric("min", checker_->min());
    ctx.metric("max", checker_->max());
    ctx.metric("last", checker_->last());
    ctx.metric("digest", checker_->digest());
    ctx.metric("passed", violations_.empty() && end.empty() ? 1.0 : 0.0);
    for (const auto& v : end) ctx.fail(v);
  }

 private:
  std::optional<testing::StreamChecker> checker_;
  std::int64_t finish_after_ = 0;
  std::vector<std::string> violations_;
  Input<msgs::Scalar> in_;
};

}  // namespace

BRICKYARD_PLUGINS(AssertSink)
