// testing.assert_sink: checks a Scalar stream and fails the run (exit 1) on any violation.
#include "assert_sink/stream_checker.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <optional>

namespace {

using namespace brickyard;

struct Settings {
  testing::StreamExpectations expect;
  std::int64_t finish_after = 0;
};

ParamBinding<Settings> bindings() {
  using E = testing::StreamExpectations;
  ParamBinding<Settings> b;
  b.bind("min_count", &Settings::expect, &E::min_count).at_least(0);
  b.bind("max_count", &Settings::expect, &E::max_count).at_least(-1).doc("-1: no limit");
  b.bind("min_value", &Settings::expect, &E::min_value).doc("NaN: no check");
  b.bind("max_value", &Settings::expect, &E::max_value).doc("NaN: no check");
  b.bind("ordering", &Settings::expect, &E::ordering).one_of({"none", "increasing", "nondecreasing", "decreasing"});
  b.bind("min_rate_hz", &Settings::expect, &E::min_rate_hz).in_unit("Hz").doc("over sample stamps; NaN: no check");
  b.bind("max_rate_hz", &Settings::expect, &E::max_rate_hz).in_unit("Hz").doc("over sample stamps; NaN: no check");
  b.bind("expect_values", &Settings::expect, &E::expect_values).doc("the first samples must equal these");
  b.bind("finish_after", &Settings::finish_after).at_least(0)
      .doc("end the run successfully after this many samples; 0: never");
  b.not_above("min_value", "max_value");
  b.not_above("min_rate_hz", "max_rate_hz");
  return b;
}

class AssertSink : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.assert_sink", "1.0.0")
        .describe("Asserts count, rate, value range, ordering and exact values of a Scalar stream; fails the run when violated")
        .input<msgs::Scalar>("in", "the stream under test", true, 1024)
        .parameters(bindings())
        .on_input("in");
  }

  void configure(Context& ctx) override {
    Settings s = bindings().read(ctx.params());
    finish_after_ = s.finish_after;
    checker_.emplace(std::move(s.expect));
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
