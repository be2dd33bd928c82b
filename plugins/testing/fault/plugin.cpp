// testing.fault: a node that fails the way a real plugin can, at a chosen step, so the host's
// answer to each is testable from a graph (docs/reliability.md): it publishes a Scalar counter
// each step until step `at_step`, then throws, segfaults, aborts, calls exit(0), hangs in its
// step, takes `slow_s` of wall time in it, or goes silent; or it hangs in its configure or its
// deactivate.
#include <brickyard/msgs/Scalar.h>
#include <brickyard/plugin.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace {

using namespace brickyard;

enum class Mode { none, throw_, segfault, abort_, exit_, hang, slow, silent, hang_configure, hang_deactivate };

struct Settings {
  double rate_hz = 50;
  Mode mode = Mode::none;
  std::int64_t at_step = 10;
  double slow_s = 0.8;
  double step_deadline_s = 0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1e-3, 1e4);
  b.bind_choice("mode",
                {{"none", Mode::none}, {"throw", Mode::throw_}, {"segfault", Mode::segfault}, {"abort", Mode::abort_}, {"exit", Mode::exit_},
                 {"hang", Mode::hang}, {"slow", Mode::slow}, {"silent", Mode::silent}, {"hang_configure", Mode::hang_configure},
                 {"hang_deactivate", Mode::hang_deactivate}},
                &Settings::mode)
      .doc("what happens in step at_step: throw an exception, a segmentation fault (SIGSEGV), abort(), exit(0), never return, "
           "take slow_s of wall time and go on, or publish nothing from then on; or never return from configure, or from deactivate");
  b.bind("at_step", &Settings::at_step).range(0, 1e9).doc("the step (from 0) the fault happens in");
  b.bind("slow_s", &Settings::slow_s).in_unit("s").range(0, 60).doc("mode slow: the wall time that step takes");
  b.bind("step_deadline_s", &Settings::step_deadline_s).in_unit("s").range(0, 3600)
      .doc("the node's step deadline (the manifest's, Manifest::step_deadline; 0: derived from its trigger); a graph node's deadline_s has the last word");
  return b;
}

struct Ports {
  Output<msgs::Scalar> out;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("out", &Ports::out).doc("the step count, until the fault");
  return b;
}

class Fault : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.fault", "1.0.0")
        .describe("Publishes a counter each step, then fails as told at a chosen step (fault injection)")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz")
        .step_deadline("step_deadline_s");
  }
  void configure(Context& ctx) override {
    s_ = bindings().read(ctx.params());
    io_ = ports().connect(ctx);
    if (s_.mode == Mode::hang_configure) hang();
  }
  void deactivate(Context&) override {
    if (s_.mode == Mode::hang_deactivate) hang();
  }
  void step(Context& ctx) override {
    if (steps_ == s_.at_step) {
      switch (s_.mode) {
        case Mode::throw_: throw std::runtime_error("fault injected: throw at step " + std::to_string(steps_));
        case Mode::segfault: std::raise(SIGSEGV); break;
        case Mode::abort_: std::abort();
        case Mode::exit_: std::exit(0);
        case Mode::hang: hang();
        case Mode::slow: std::this_thread::sleep_for(std::chrono::duration<double>(s_.slow_s)); break;
        case Mode::silent:
        case Mode::hang_configure:
        case Mode::hang_deactivate:
        case Mode::none: break;
      }
    }
    const bool quiet = s_.mode == Mode::silent && steps_ >= s_.at_step;
    ++steps_;
    if (quiet) return;
    msgs::Scalar m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(static_cast<std::uint32_t>(steps_));
    m.value(static_cast<double>(steps_));
    io_.out.publish(std::move(m));
  }

 private:
  [[noreturn]] static void hang() {
    for (;;) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  Settings s_;
  std::int64_t steps_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Fault)
