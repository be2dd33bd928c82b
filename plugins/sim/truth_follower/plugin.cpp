// sim.truth_follower: drives the simulated car from ground truth (pure pursuit on a racing line
// with a speed profile), so graphs can drive before the real estimation and control stack.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"

#include "../common/pure_pursuit.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

class TruthFollower : public Plugin {
 public:
  static Manifest manifest() {
    const motion::VehicleLimits l;
    const PursuitParams pp;
    return Manifest("sim.truth_follower", "1.0.0")
        .describe("Pure pursuit on a racing line from ground truth (a stand-in driver for simulator graphs)")
        .input<msgs::VehicleState>("truth", "ground truth", true, 1)
        .input<msgs::TrackWorld>("world", "when wired, the line is kept edge_margin inside the track", false, 1)
        .output<msgs::ControlCommand>("command", "steer, throttle, brake")
        .param(ParamSpec::string("raceline", "racelines/IMS.csv").doc("x_m,y_m file of the line to follow"))
        .param(ParamSpec::number("rate_hz", 100).in_unit("Hz").at_least(1))
        .param(ParamSpec::number("v_max", l.v_max).in_unit("m/s").at_least(1))
        .param(ParamSpec::number("a_lat", l.a_lat).in_unit("m/s^2").at_least(0.5))
        .param(ParamSpec::number("a_accel", l.a_accel).in_unit("m/s^2").at_least(0.1))
        .param(ParamSpec::number("a_decel", l.a_decel).in_unit("m/s^2").at_least(0.1))
        .param(ParamSpec::number("edge_margin", 2.5).in_unit("m").at_least(0)
                   .doc("closest the line's points may come to a track edge (needs the world input)"))
        .param(ParamSpec::number("lookahead_min", pp.lookahead_min).in_unit("m").at_least(0.5))
        .param(ParamSpec::number("lookahead_time", pp.lookahead_time).in_unit("s").at_least(0))
        .param(ParamSpec::number("speed_gain", pp.speed_gain).at_least(0))
        .param(plugins::vehicle_param())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    const std::string path = ctx.find_file(p.string("raceline"));
    CenterLine xy;
    try {
      xy = load_xy_csv(path);
    } catch (const TrackFileError& e) {
      throw BadInput(std::string("raceline file ") + e.what());
    }
    line_ = xy;
    margin_ = p.number("edge_margin");
    limits_ = motion::independent_limits(p.number("v_max"), p.number("a_lat"), p.number("a_accel"), p.number("a_decel"));
    const vehicle::Vehicle car = plugins::read_vehicle(ctx);
    PursuitParams& pp = pursuit_params_;
    pp.wheelbase = car.wheelbase;
    pp.max_steer = car.max_steer;
    pp.lookahead_min = p.number("lookahead_min");
    pp.lookahead_time = p.number("lookahead_time");
    pp.speed_gain = p.number("speed_gain");
    world_ = ctx.input<msgs::TrackWorld>("world");
    truth_ = ctx.input<msgs::VehicleState>("truth");
    out_ = ctx.output<msgs::ControlCommand>("command");
  }

  void step(Context& ctx) override {
    if (!pursuit_) {
      // With a world wired, wait for it and keep the line inside the track; without, use the file.
      CenterLine line = line_;
      if (world_.connected()) {
        auto w = newest(world_);
        if (!w) return;
        Track t(from_message(*w));
        line = motion::keep_inside(line_, t, margin_);
      }
      pursuit_ = std::make_unique<PurePursuit>(motion::make_racing_line(line, limits_), pursuit_params_);
    }
    auto s = newest(truth_);
    if (!s) return;
    double target = 0;
    Command c = pursuit_->control(s->x(), s->y(), s->yaw(), s->vx(), &target);
    msgs::ControlCommand m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.steer(c.steer);
    m.throttle(c.throttle);
    m.brake(c.brake);
    m.target_speed(target);
    m.source("truth_follower");
    out_.publish(std::move(m));
  }

 private:
  CenterLine line_;
  double margin_ = 2.5;
  motion::VehicleLimits limits_;
  PursuitParams pursuit_params_;
  std::unique_ptr<PurePursuit> pursuit_;
  Input<msgs::TrackWorld> world_;
  std::uint32_t seq_ = 0;
  Input<msgs::VehicleState> truth_;
  Output<msgs::ControlCommand> out_;
};

}  // namespace

BRICKYARD_PLUGINS(TruthFollower)
