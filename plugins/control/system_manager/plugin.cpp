// control.system_manager: chooses the command that reaches the car from the localization status
// and the wall estimate (common/system_manager.hpp): the path tracker's, the wall follower's, or
// a safe stop; then obeys race control's flags (common/flag_gate.hpp: a yellow's cap, a
// controlled stop). Publishes ModeStatus; logs and counts every transition.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/RaceControl.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "control/command_msg.hpp"
#include "control/common/mode_command.hpp"
#include "control/common/mode_stats.hpp"
#include "control/common/system_manager.hpp"
#include "messages.hpp"
#include "params.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::control;

struct Ports {
  Input<msgs::ModeStatus> localization;
  Input<msgs::WallEstimate> wall;
  Input<msgs::ControlCommand> path_command, wall_command;
  Input<msgs::RaceControl> race_control;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::VehicleStatus> vehicle;
  Output<msgs::ControlCommand> command;
  Output<msgs::ModeStatus> mode;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("localization", &Ports::localization).doc("the localization manager's status (the estimator's mode output)");
  b.input("wall", &Ports::wall).doc("the wall detector's estimate: is there a wall to follow (unwired: never)").optional().depth(8);
  b.input("path_command", &Ports::path_command).doc("the path tracker's command").depth(8);
  b.input("wall_command", &Ports::wall_command).doc("the wall follower's command (unwired: no fallback controller)").optional().depth(8);
  b.input("race_control", &Ports::race_control).doc("race control's flags (the vehicle interface's; unwired: none obeyed)").optional().depth(16);
  b.input("estimate", &Ports::estimate).doc("the car's speed, for a yellow flag's cap").optional().depth(8);
  b.input("vehicle", &Ports::vehicle).doc("the vehicle interface's status: a car side that stops the car or falls silent stops it (unwired: not watched)").optional().depth(8);
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
        .periodic("rate_hz").step_deadline("step_deadline_s")
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    manager_ = SystemManager(s.manager);
    gate_.emplace(s.flags, stop_brake(plugins::read_vehicle(ctx, s.vehicle), s.flags.stop_decel_mps2));
    io_ = ports().connect(ctx);
    if (io_.vehicle.connected()) manager_.watch_vehicle();
  }

  void step(Context& ctx) override {
    const double t = ctx.now_s();
    if (!ctx.sim_clock() && !started_) manager_.started(t), started_ = true;
    take_inputs();
    const Transition tr = manager_.update(t);
    if (tr.happened) ctx.log(LogLevel::info, transition_line(tr, t));
    if (stats_.step(t, tr, manager_.mode())) ctx.status("mode", mode_name(manager_.mode()));
    if (io_.race_control.connected()) obey_flags(ctx, t);
    publish(ctx, t);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : stats_.metrics()) ctx.metric(name, value);
    ctx.metric("final_mode", std::string(mode_name(manager_.mode())));
    if (!io_.race_control.connected()) return;
    ctx.metric("race_state", std::string(race_state_name(gate_->state())));
    ctx.metric("race_transitions", static_cast<double>(race_transitions_));
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
    for (auto& v : io_.vehicle.take()) manager_.vehicle(stamp(v->header().stamp_ns()), vehicle_health(*v));
    for (auto& c : io_.wall_command.take()) {
      last_wall_ = c;
      manager_.wall_command(stamp(c->header().stamp_ns()));
    }
  }

  void obey_flags(Context& ctx, double t) {
    for (auto& m : io_.race_control.take())
      gate_->flags({stamp(m->header().stamp_ns()), m->heard(), motion::track_flag_of(m->track_flag()),
                    motion::vehicle_flag_of(m->vehicle_flag()), m->target_speed(), m->lap()});
    for (auto& e : io_.estimate.take()) gate_->speed(stamp(e->header().stamp_ns()), e->speed());
    const FlagTransition tr = gate_->update(t);
    if (!tr.happened) return;
    ++race_transitions_;
    ctx.log(LogLevel::info, flag_line(tr, t));
    ctx.status("flags", race_state_name(gate_->state()));
  }

  void publish(Context& ctx, double t) {
    const Mode mode = manager_.mode();
    ManagerParams p = manager_.params();
    p.stop_on_path = p.stop_on_path || manager_.stopped_for_car();
    ModeCommand out = command_for(mode, t, plain(last_path_), plain(last_wall_), p);
    if (io_.race_control.connected()) out.command = gate_->apply(out.command, t);
    const CommandPtr from = out.forward == Forwarded::path ? last_path_ : out.forward == Forwarded::wall ? last_wall_ : nullptr;
    msgs::ControlCommand c = command_message(out.command, controller_name(mode), ctx.now_ns(), seq_);
    c.header().frame_id(from ? from->header().frame_id() : "");  // a forwarded command keeps its frame
    io_.command.publish(std::move(c));
    io_.mode.publish(mode_message(mode, stats_.reason(), controller_name(mode), ctx.now_ns(), seq_++));
  }

  SystemManager manager_;
  bool started_ = false;
  std::optional<FlagGate> gate_;
  std::uint64_t race_transitions_ = 0;
  ModeStats stats_;
  Ports io_;
  CommandPtr last_path_, last_wall_;
  std::uint32_t seq_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(SystemManagerNode)
