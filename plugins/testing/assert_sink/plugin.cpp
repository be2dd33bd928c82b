// testing.assert_sink: checks a Scalar stream and fails the run (exit 1) on any violation.
#include "testing/assert_sink/stream_checker.hpp"

#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace {

using namespace brickyard;

struct Settings {
  testing::StreamExpectations expect;
  std::int64_t finish_after = 0;
  double min_age_s = NAN, max_age_s = NAN;  // a sample's age when it arrives: now - its stamp
};

ParamBinding<Settings> bindings() {
  using E = testing::StreamExpectations;
  ParamBinding<Settings> b;
  b.bind("min_count", &Settings::expect, &E::min_count).range(0, 1e9);
  b.bind("max_count", &Settings::expect, &E::max_count).range(-1, 1e9).doc("-1: no limit");
  b.bind("min_value", &Settings::expect, &E::min_value).range(-1e6, 1e6).doc("NaN: no check");
  b.bind("max_value", &Settings::expect, &E::max_value).range(-1e6, 1e6).doc("NaN: no check");
  b.bind("ordering", &Settings::expect, &E::ordering).one_of({"none", "increasing", "nondecreasing", "decreasing"});
  b.bind("min_rate_hz", &Settings::expect, &E::min_rate_hz).in_unit("Hz").range(0, 1e6)
      .doc("over sample stamps; NaN: no check");
  b.bind("max_rate_hz", &Settings::expect, &E::max_rate_hz).in_unit("Hz").range(0, 1e6)
      .doc("over sample stamps; NaN: no check");
  b.bind("expect_values", &Settings::expect, &E::expect_values).range(-1e6, 1e6)
      .doc("the first samples must equal these");
  b.bind("finish_after", &Settings::finish_after).range(0, 1e9)
      .doc("end the run successfully after this many samples; 0: never");
  b.bind("min_age_s", &Settings::min_age_s).in_unit("s").range(-3600, 3600).doc("each sample at least this old when it arrives (now - stamp); NaN: no check");
  b.bind("max_age_s", &Settings::max_age_s).in_unit("s").range(-3600, 3600).doc("each sample at most this old when it arrives; NaN: no check");
  b.not_above("min_value", "max_value");
  b.not_above("min_age_s", "max_age_s");
  b.not_above("min_rate_hz", "max_rate_hz");
  return b;
}

struct Ports {
  Input<msgs::Scalar> in;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("in", &Ports::in).doc("the stream under test").depth(1024).steps();
  return b;
}

class AssertSink : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.assert_sink", "1.0.0")
        .describe("Asserts count, rate, value range, ordering and exact values of a Scalar stream; fails the run when violated")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    Settings s = bindings().read(ctx.params());
    finish_after_ = s.finish_after;
    min_age_ = s.min_age_s;
    max_age_ = s.max_age_s;
    checker_.emplace(std::move(s.expect));
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& s : io_.in.take()) {
      if (auto v = checker_->observe(s->header().stamp_ns(), s->value())) {
        violations_.push_back(*v);
        ctx.fail(*v);
      }
      const double age = static_cast<double>(ctx.now_ns() - s->header().stamp_ns()) * 1e-9;
      max_seen_age_ = std::max(max_seen_age_, age);
      if (age < min_age_ - 1e-9 || age > max_age_ + 1e-9) {
        char b[160];
        std::snprintf(b, sizeof b, "sample %lld stamped %.6f s arrived %.6f s old (expected %g to %g s)",
                      static_cast<long long>(checker_->count()), static_cast<double>(s->header().stamp_ns()) * 1e-9, age,
                      min_age_, max_age_);
        violations_.push_back(b);
        ctx.fail(b);
      }
      if (finish_after_ > 0 && checker_->count() == finish_after_) ctx.finish("received " + std::to_string(finish_after_) + " samples");
    }
  }

  void deactivate(Context& ctx) override {
    for (const auto& s : io_.in.take()) checker_->observe(s->header().stamp_ns(), s->value());
    auto end = checker_->finish();
    ctx.metric("count", static_cast<double>(checker_->count()));
    ctx.metric("rate_hz", checker_->rate_hz());
    ctx.metric("min", checker_->min());
    ctx.metric("max", checker_->max());
    ctx.metric("last", checker_->last());
    ctx.metric("digest", checker_->digest());
    ctx.metric("max_age_s", max_seen_age_);
    ctx.metric("passed", violations_.empty() && end.empty() ? 1.0 : 0.0);
    for (const auto& v : end) ctx.fail(v);
  }

 private:
  std::optional<testing::StreamChecker> checker_;
  std::int64_t finish_after_ = 0;
  double min_age_ = NAN, max_age_ = NAN, max_seen_age_ = 0;
  std::vector<std::string> violations_;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(AssertSink)
