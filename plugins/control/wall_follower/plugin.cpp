// control.wall_follower: the paper's wall command u_w = w_θ y′(L) + w_d (d_w − d_gap) from the
// wall detector's estimate, with a speed policy (common/wall_follower.hpp).
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "../command_msg.hpp"
#include "common/wall_follower.hpp"
#include "vehicle_param.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::control;

// What the graph says: the law's parameters, and the car whose steering limit it keeps.
struct Settings {
  WallFollowerParams law;
  std::string vehicle = plugins::default_vehicle_file;
  std::optional<double> max_steer;  // NaN: the vehicle file's
};

ParamBinding<Settings> bindings() {
  using P = WallFollowerParams;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its steering limit");
  b.bind_choice("side", {{"right", -1}, {"left", 1}}, &Settings::law, &P::side).doc("the wall followed");
  b.bind("w_theta", &Settings::law, &P::w_theta).doc("rad of steer per unit of the wall's slope at the look-ahead");
  b.bind("w_d", &Settings::law, &P::w_d).in_unit("rad/m").doc("rad of steer per m of gap error");
  b.bind("gap", &Settings::law, &P::gap).in_unit("m").at_least(0).doc("distance kept to the wall");
  b.bind("lookahead", &Settings::law, &P::lookahead).in_unit("m").at_least(0);
  b.bind("max_steer", &Settings::max_steer).in_unit("rad").at_least(0.01).doc("steering limit; default: the vehicle file's");
  b.bind("schedule_above", &Settings::law, &P::schedule_above).in_unit("m/s").at_least(0)
      .doc("above this speed the look-ahead grows and the gains shrink with speed as a pure pursuit's; 0: fixed");
  b.bind_choice("speed_policy", {{"reduce", true}, {"hold", false}}, &Settings::law, &P::reduce_speed)
      .doc("while following: slow to fallback_speed, or hold");
  b.bind("fallback_speed", &Settings::law, &P::fallback_speed).in_unit("m/s").at_least(0);
  b.bind("decel", &Settings::law, &P::decel).in_unit("m/s^2").at_least(0.1);
  b.bind("a_lat", &Settings::law, &P::a_lat).in_unit("m/s^2").at_least(0).doc("the wall's bend caps the speed at sqrt(a_lat / curvature); 0: off");
  b.bind("speed_gain", &Settings::law, &P::speed_gain).at_least(0);
  return b;
}

class WallFollowerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.wall_follower", "1.0.0")
        .describe("the paper's wall-following command u_w = w_theta y'(L) + w_d (d_w - d_gap), holding or reducing speed")
        .input<msgs::WallEstimate>("wall", "the wall detector's estimate", true, 4)
        .input<msgs::WheelSpeeds>("wheels", "speed, independent of GNSS", true, 16)
        .input<msgs::ModeStatus>("mode", "the system manager's mode: taking over starts the speed policy (optional)", false, 8)
        .output<msgs::ControlCommand>("command", "steer and pedals, source \"wall_follower\"")
        .parameters(bindings())
        .on_input("wall");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    WallFollowerParams law = s.law;
    law.max_steer = s.max_steer.value_or(plugins::read_vehicle(ctx, s.vehicle).max_steer);
    follower_ = WallFollower(law);
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
