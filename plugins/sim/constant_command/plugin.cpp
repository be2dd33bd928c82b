// sim.constant_command: an open-loop driver for tests: the same steer, throttle and brake,
// from start_s on (nothing before it).
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

namespace {

using namespace brickyard;

class ConstantCommand : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.constant_command", "1.0.0")
        .describe("Open-loop command for tests: constant steer, throttle and brake")
        .output<msgs::ControlCommand>("command", "the command")
        .param(ParamSpec::number("steer", 0).in_unit("rad").doc("road-wheel angle, left positive"))
        .param(ParamSpec::number("throttle", 0).range(0, 1))
        .param(ParamSpec::number("brake", 0).range(0, 1))
        .param(ParamSpec::number("start_s", 0).in_unit("s").at_least(0))
        .param(ParamSpec::number("rate_hz", 50).in_unit("Hz").at_least(0.1))
        .periodic("rate_hz");
  }
  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    steer_ = p.number("steer");
    throttle_ = p.number("throttle");
    brake_ = p.number("brake");
    start_ = p.number("start_s");
    out_ = ctx.output<msgs::ControlCommand>("command");
  }
  void step(Context& ctx) override {
    if (ctx.now_s() < start_) return;
    msgs::ControlCommand m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.steer(steer_);
    m.throttle(throttle_);
    m.brake(brake_);
    m.source(ctx.node_name());
    out_.publish(std::move(m));
  }

 private:
  double steer_ = 0, throttle_ = 0, brake_ = 0, start_ = 0;
  std::uint32_t seq_ = 0;
  Output<msgs::ControlCommand> out_;
};

}  // namespace

BRICKYARD_PLUGINS(ConstantCommand)
