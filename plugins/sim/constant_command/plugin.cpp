// sim.constant_command: an open-loop driver for tests: the same steer, throttle and brake,
// from start_s on (nothing before it).
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include "sim/run_time.hpp"

namespace {

using namespace brickyard;
using brickyard::sim::RunTime;

struct Settings {
  double steer = 0, throttle = 0, brake = 0, start_s = 0;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("steer", &Settings::steer).in_unit("rad").range(-1.5, 1.5).doc("road-wheel angle, left positive");
  b.bind("throttle", &Settings::throttle).range(0, 1);
  b.bind("brake", &Settings::brake).range(0, 1);
  b.bind("start_s", &Settings::start_s).in_unit("s").range(0, 1e7);
  b.declare(ParamSpec::number("rate_hz", 50).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  return b;
}

struct Ports {
  Output<msgs::ControlCommand> command;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output("command", &Ports::command).doc("the command");
  return b;
}

class ConstantCommand : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.constant_command", "1.0.0")
        .describe("Open-loop command for tests: constant steer, throttle and brake")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz");
  }
  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    steer_ = s.steer;
    throttle_ = s.throttle;
    brake_ = s.brake;
    start_ = s.start_s;
    io_ = ports().connect(ctx);
  }
  void step(Context& ctx) override {
    if (run_.now_s(ctx) < start_) return;
    msgs::ControlCommand m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.steer(steer_);
    m.throttle(throttle_);
    m.brake(brake_);
    m.source(ctx.node_name());
    io_.command.publish(std::move(m));
  }

 private:
  double steer_ = 0, throttle_ = 0, brake_ = 0, start_ = 0;
  std::uint32_t seq_ = 0;
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(ConstantCommand)
