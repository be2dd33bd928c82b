// control.system_manager: chooses the command that reaches the car from the localization status
// and the wall estimate (common/system_manager.hpp): the path tracker's, the wall follower's, or
// a safe stop. Publishes ModeStatus; logs and counts every transition.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "control/command_msg.hpp"
#include "control/common/mode_command.hpp"
#include "control/common/mode_stats.hpp"
#include "control/common/system_manager.hpp"
#include "params.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::control;

struct Ports {
  Input<msgs::ModeStatus> localization;
  Input<msgs::WallEstimate> wall;
  Input<msgs::ControlCommand> path_command, wall_command;
  Output<msgs::ControlCommand> command;
  Output<msgs::ModeStatus> mode;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("localization", &Ports::localization).doc("the localization manager's status (the estimator's mode output)");
  b.input("wall", &Ports::wall).doc("the wall detector's estimate: is there a wall to follow").depth(8);
  b.input("path_command", &Ports::path_command).doc("the path tracker's command").depth(8);
  b.input("wall_command", &Ports::wall_command).doc("the wall follower's command").depth(8);
  b.output("command", &Ports::command).doc("to the car");
  b.output("mode", &Ports::mode).doc("PATH / WALL_FOLLOW / SAFE_STOP, on change and every step");
  return b;
}

class SystemManagerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.system_manager", "1.0.0")
        .describe("localization EMERGENCY hands steering to the wall follower; back to the path tracker once NORMAL has held; "
                  "a safe stop when the wall is lost too")
        .with_ports(ports()).plays(roles::system_manager).parameters(bindings())
        .periodic("rate_hz").step_deadline("step_deadline_s");
  }

  void configure(Context& ctx) override {
    manager_ = SystemManager(bindings().read(ctx.params()).manager);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    const double t = ctx.now_s();
    take_inputs();
    const Transition tr = manager_.update(t);
    if (tr.happened) ctx.log(LogLevel::info, transition_line(tr, t));
    if (stats_.step(t, tr, manager_.mode())) ctx.status("mode", mode_name(manager_.mode()));
    publish(ctx, t);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : stats_.metrics()) ctx.metric(name, value);
    ctx.metric("final_mode", std::string(mode_name(manager_.mode())));
  }

 private:
  using CommandPtr = std::shared_ptr<const msgs::ControlCommand>;
  static double stamp(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
  static std::optional<ControllerCommand> plain(const CommandPtr& c) {
    if (!c) return std::nullopt;
    return ControllerCommand{stamp(c->header().stamp_ns()), {c->steer(), c->throttle(), c->brake(), c->target_speed()}};
  }

  void take_inputs() {
    for (auto& s : io_.localization.take())
      manager_.status(stamp(s->header().stamp_ns()), static_cast<LocStatus>(std::min<int>(s->mode(), 2)));
    for (auto& w : io_.wall.take()) manager_.wall(stamp(w->header().stamp_ns()), w->valid());
    for (auto& c : io_.path_command.take()) {
      last_path_ = c;
      manager_.path_command(stamp(c->header().stamp_ns()));
    }
    for (auto& c : io_.wall_command.take()) {
      last_wall_ = c;
      manager_.wall_command(stamp(c->header().stamp_ns()));
    }
  }

  void publish(Context& ctx, double t) {
    const Mode mode = manager_.mode();
    const ModeCommand out = command_for(mode, t, plain(last_path_), plain(last_wall_), manager_.params());
    const CommandPtr from = out.forward == Forwarded::path ? last_path_ : out.forward == Forwarded::wall ? last_wall_ : nullptr;
    msgs::ControlCommand c = command_message(out.command, controller_name(mode), ctx.now_ns(), seq_);
    c.header().frame_id(from ? from->header().frame_id() : "");  // a forwarded command keeps its frame
    io_.command.publish(std::move(c));
    msgs::ModeStatus m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.mode(mode_number(mode));
    m.mode_name(mode_name(mode));
    m.reason(stats_.reason());
    m.active_controller(controller_name(mode));
    io_.mode.publish(std::move(m));
  }

  SystemManager manager_;
  ModeStats stats_;
  Ports io_;
  CommandPtr last_path_, last_wall_;
  std::uint32_t seq_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(SystemManagerNode)
