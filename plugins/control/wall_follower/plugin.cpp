// control.wall_follower: the paper's wall command u_w = w_θ y′(L) + w_d (d_w − d_gap) from the
// wall detector's estimate, with a speed policy (common/wall_follower.hpp).
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "../command_msg.hpp"
#include "common/wall_follower.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::control;

class WallFollowerNode : public Plugin {
 public:
  static Manifest manifest() {
    const WallFollowerParams d;
    return Manifest("control.wall_follower", "1.0.0")
        .describe("the paper's wall-following command u_w = w_theta y'(L) + w_d (d_w - d_gap), holding or reducing speed")
        .input<msgs::WallEstimate>("wall", "the wall detector's estimate", true, 4)
        .input<msgs::WheelSpeeds>("wheels", "speed, independent of GNSS", true, 16)
        .input<msgs::ModeStatus>("mode", "the system manager's mode: taking over starts the speed policy (optional)", false, 8)
        .output<msgs::ControlCommand>("command", "steer and pedals, source \"wall_follower\"")
        .param(ParamSpec::string("side", "right").one_of({"right", "left"}).doc("the wall followed"))
        .param(ParamSpec::number("w_theta", d.w_theta).doc("rad of steer per unit of the wall's slope at the look-ahead"))
        .param(ParamSpec::number("w_d", d.w_d).in_unit("rad/m").doc("rad of steer per m of gap error"))
        .param(ParamSpec::number("gap", d.gap).in_unit("m").at_least(0).doc("distance kept to the wall"))
        .param(ParamSpec::number("lookahead", d.lookahead).in_unit("m").at_least(0))
        .param(ParamSpec::number("max_steer", d.max_steer).in_unit("rad").at_least(0.01))
        .param(ParamSpec::number("schedule_above", d.schedule_above).in_unit("m/s").at_least(0)
                   .doc("above this speed the look-ahead grows and the gains shrink with speed as a pure pursuit's; 0: fixed"))
        .param(ParamSpec::string("speed_policy", "reduce").one_of({"reduce", "hold"}).doc("while following: slow to fallback_speed, or hold"))
        .param(ParamSpec::number("fallback_speed", d.fallback_speed).in_unit("m/s").at_least(0))
        .param(ParamSpec::number("decel", d.decel).in_unit("m/s^2").at_least(0.1))
        .param(ParamSpec::number("a_lat", d.a_lat).in_unit("m/s^2").at_least(0).doc("the wall's bend caps the speed at sqrt(a_lat / curvature); 0: off"))
        .param(ParamSpec::number("speed_gain", d.speed_gain).at_least(0))
        .on_input("wall");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    WallFollowerParams wp;
    wp.side = p.string("side") == "left" ? 1 : -1;
    wp.w_theta = p.number("w_theta");
    wp.w_d = p.number("w_d");
    wp.gap = p.number("gap");
    wp.lookahead = p.number("lookahead");
    wp.max_steer = p.number("max_steer");
    wp.schedule_above = p.number("schedule_above");
    wp.reduce_speed = p.string("speed_policy") == "reduce";
    wp.fallback_speed = p.number("fallback_speed");
    wp.decel = p.number("decel");
    wp.a_lat = p.number("a_lat");
    wp.speed_gain = p.number("speed_gain");
    follower_ = WallFollower(wp);
    wall_ = ctx.input<msgs::WallEstimate>("wall");
    wheels_ = ctx.input<msgs::WheelSpeeds>("wheels");
    mode_ = ctx.input<msgs::ModeStatus>("mode");
    out_ = ctx.output<msgs::ControlCommand>("command");
  }

  void step(Context& ctx) override {
    for (auto& w : wheels_.take()) speed_ = 0.5 * (w->rear_left() + w->rear_right());
    const double t = ctx.now_s();
    for (auto& m : mode_.take()) {
      const bool active = m->active_controller() == "wall_follower";
      if (active && !active_) {
        follower_.engage(t, speed_);
        ++engaged_;
      }
      active_ = active;
    }
    for (auto& w : wall_.take()) {
      if (!mode_.connected() && !engaged_) {  // no manager to say when: from the first estimate
        follower_.engage(t, speed_);
        ++engaged_;
      }
      // Not driving yet: the speed policy starts from now, so the command the manager forwards at
      // the handover holds the car's speed instead of braking for a stale target.
      if (mode_.connected() && !active_) follower_.engage(t, speed_);
      WallView v{w->coefficients(), w->valid()};
      const Command c = follower_.control(t, v, speed_);
      out_.publish(command_message(c, "wall_follower", w->header().stamp_ns(), seq_++));
      invalid_ += !w->valid();
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("commands", static_cast<double>(seq_));
    ctx.metric("engaged", static_cast<double>(engaged_));
    ctx.metric("invalid_walls", static_cast<double>(invalid_));
  }

 private:
  WallFollower follower_;
  Input<msgs::WallEstimate> wall_;
  Input<msgs::WheelSpeeds> wheels_;
  Input<msgs::ModeStatus> mode_;
  Output<msgs::ControlCommand> out_;
  double speed_ = 0;
  bool active_ = false;
  std::uint32_t seq_ = 0;
  std::uint64_t engaged_ = 0, invalid_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(WallFollowerNode)
