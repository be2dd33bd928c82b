// testing.expect: checks fields of any message type, decoded by the wire's IDL — ranges, values,
// order, "always" and "eventually" within time windows, the stream's count and rate, and
// nearness to a second wire ("ref") — and reports every expectation that failed at the end of the
// run (exit 1), each with its field, sample and time. docs/testing.md.
#include <brickyard/plugin.hpp>

#include "expectations.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;

struct Settings {
  std::string expect = "[]";
  std::int64_t finish_after = 0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_json("expect", &Settings::expect)
      .doc("the expectations: [{\"field\": \"poses[*].x\", \"range\": [-10, 10]}, {\"count\": [5, 100]}, ...] (docs/testing.md)");
  b.bind("finish_after", &Settings::finish_after).range(0, 1e9).doc("end the run, successfully, after this many samples (0: never)");
  return b;
}

// Named once: check() asks the validator about the same ports.
constexpr char kIn[] = "in", kRef[] = "ref";

struct Ports {
  AnyInput in, ref;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input(kIn, &Ports::in).doc("the stream under test: any message type").depth(1024).steps();
  b.input(kRef, &Ports::ref).doc("a second stream to compare with (near): its newest sample").optional().depth(64);
  return b;
}

class Expect : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.expect", "1.0.0")
        .describe("Checks fields of any message type by path (range, equals, order, near a second wire; always or "
                  "eventually in a time window; count, rate) and reports every failed expectation at the end")
        .with_ports(ports())
        .parameters(bindings())
        .check(&Expect::check);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    finish_after_ = s.finish_after;
    io_ = ports().connect(ctx);
    idl_.emplace(io_.in.idl() ? io_.in.idl() : "");
    if (io_.ref.connected() && io_.ref.idl()) ref_idl_.emplace(io_.ref.idl());
    checker_.emplace(parse(s, *idl_, io_.in.type_name(), ref_idl_ ? &*ref_idl_ : nullptr, io_.ref.type_name()));
  }

  // At validation: the same parse, on the types the wires will carry.
  static void check(const CheckView& v) {
    const Settings s = bindings().read(v.params());
    const char* ref = v.port_type(kRef).empty() ? nullptr : v.port_idl(kRef);
    const cdr::CdrJson idl(v.port_idl(kIn) ? v.port_idl(kIn) : "");
    std::optional<cdr::CdrJson> ref_idl;
    if (ref) ref_idl.emplace(ref);
    parse(s, idl, v.port_type(kIn), ref_idl ? &*ref_idl : nullptr, v.port_type(kRef));
  }

  void step(Context& ctx) override { read(ctx); }

  void deactivate(Context& ctx) override {
    read(ctx);
    const auto failed = checker_->finish();
    ctx.metric("samples", static_cast<double>(checker_->samples()));
    ctx.metric("field_checks", static_cast<double>(checker_->field_checks()));
    ctx.metric("expectations", static_cast<double>(checker_->size()));
    ctx.metric("failed", static_cast<double>(failed.size() + decode_errors_.size()));
    ctx.metric("digest", checker_->digest());  // every sample's time and bytes: the same run, the same digest
    std::vector<std::string> all = decode_errors_;
    all.insert(all.end(), failed.begin(), failed.end());
    for (std::size_t i = 0; i < all.size(); ++i) {
      ctx.log(LogLevel::error, "expectation failed: " + all[i]);
      ctx.metric("failure_" + std::to_string(i), all[i]);
    }
    if (!all.empty())
      ctx.fail(std::to_string(all.size()) + " of " + std::to_string(checker_->size()) + " expectations failed" +
               (all.size() > 1 ? " (each above); the first: " : ": ") + all[0]);
  }

 private:
  static testing::ExpectationChecker parse(const Settings& s, const cdr::CdrJson& idl, const std::string& type,
                                           const cdr::CdrJson* ref_idl, const std::string& ref_type) {
    try {
      return testing::ExpectationChecker(testing::parse_expectations(nlohmann::json::parse(s.expect), idl, type, ref_idl, ref_type));
    } catch (const std::invalid_argument& e) {
      throw BadInput("parameter 'expect' " + std::string(e.what()) + " (" + type + ")");
    } catch (const nlohmann::json::exception& e) {
      throw BadInput(std::string("parameter 'expect': ") + e.what());
    }
  }

  void read(Context& ctx) {
    for (const auto& r : io_.ref.take()) {
      try {
        checker_->reference(ref_idl_->decode(io_.ref.type_name(), r->cdr.data(), r->cdr.size()));
      } catch (const std::exception& e) {
        if (decode_errors_.size() < 8) decode_errors_.push_back("ref: a sample does not decode: " + std::string(e.what()));
      }
    }
    for (const auto& m : io_.in.take()) {
      checker_->feed(ctx.now_s(), m->cdr.data(), m->cdr.size());
      try {
        checker_->observe(ctx.now_s(), idl_->decode(io_.in.type_name(), m->cdr.data(), m->cdr.size()));
      } catch (const std::exception& e) {
        if (decode_errors_.size() < 8) decode_errors_.push_back("in: a sample does not decode: " + std::string(e.what()));
      }
      if (finish_after_ > 0 && checker_->samples() == static_cast<std::uint64_t>(finish_after_))
        ctx.finish("received " + std::to_string(finish_after_) + " samples");
    }
  }

  std::int64_t finish_after_ = 0;
  Ports io_;
  std::optional<cdr::CdrJson> idl_, ref_idl_;
  std::optional<testing::ExpectationChecker> checker_;
  std::vector<std::string> decode_errors_;
};

}  // namespace

BRICKYARD_PLUGINS(Expect)
