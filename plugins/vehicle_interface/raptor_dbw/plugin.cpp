// vehicle_interface.raptor_dbw: the stack's ControlCommand to the car's drive-by-wire (New Eagle's
// Raptor on the AV-21) over CAN, from the car's DBC, and its reports back as WheelSpeeds and
// VehicleStatus, and race control's flags as RaceControl (acknowledged in ct_report). Each period
// the bus is read without blocking and the commands due are sent (common/raptor_interface.hpp:
// rates, rolling counters, the gear, the team's heartbeat, the command watchdog, race control).
// docs/vehicle-interface.md, docs/race-control.md.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/VehicleStatus.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "vehicle_interface/raptor_dbw/metrics.hpp"
#include "vehicle_interface/raptor_dbw/params.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::vehicle_interface;

void check(const CheckView& v) { read_setup(v, bindings().read(v.params())); }

struct Ports {
  Input<msgs::ControlCommand> command;
  Output<msgs::WheelSpeeds> speeds;
  Output<msgs::VehicleStatus> status;
  Output<msgs::RaceControl> race_control;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("command", &Ports::command).doc("steer, throttle, brake: driven until command_timeout_s old, then a stop").depth(16);
  b.output("speeds", &Ports::speeds).doc("the four wheel speeds of wheel_speed_report, m/s, stamped at receipt");
  b.output("status", &Ports::status).doc("the reports (steering, brakes, gear, rpm, diagnostics) and the interface's state, at status_hz");
  b.output("race_control", &Ports::race_control).doc("race control's flags, target speed, lap and heartbeat: on each frame, at status_hz");
  return b;
}

class RaptorDbw : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("vehicle_interface.raptor_dbw", "1.0.0")
        .describe("the stack's commands to the car's drive-by-wire over CAN (SocketCAN, or cannelloni over UDP) from its DBC; its reports back")
        .with_ports(ports())
        .plays(roles::vehicle_interface)
        .plays(roles::wheel_speed_driver)
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    Setup setup = read_setup(ctx, s);
    std::string error;
    bus_ = open_bus(setup.bus, error);
    if (!bus_) throw BadInput("parameter 'bus': " + error);
    if (setup.race_control_bus && !(race_bus_ = open_udp_receiver(*setup.race_control_bus, error)))
      throw BadInput("parameter 'race_control_bus': " + error);
    iface_.emplace(std::move(*setup.mapping), setup.params, std::move(setup.race_control));
    status_period_ns_ = static_cast<std::int64_t>(1e9 / s.status_hz);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    for (const auto& c : io_.command.take())
      if (std::string why = iface_->command({c->steer(), c->throttle(), c->brake(), c->target_speed()}); !why.empty())
        if (iface_->counts().bad_commands <= 20) warn(ctx, "command refused: " + why);  // then only counted
    frames_.clear();
    if (!bus_->poll(frames_) || (race_bus_ && !race_bus_->poll(frames_))) device_failed(ctx);
    for (const std::string& w : iface_->receive(frames_, now)) warn(ctx, w);
    const std::uint64_t wheel_reports = iface_->monitor().counts(RaptorMessage::wheel_speed_report).received;
    if (wheel_reports != wheel_reports_) publish_speeds(now), wheel_reports_ = wheel_reports;
    const InterfaceStep out = iface_->step(now);
    for (const std::string& w : out.warnings) warn(ctx, w);
    for (const std::string& n : out.notes) ctx.log(LogLevel::info, n);
    const bool changed = !out.state_change.empty();
    if (changed) {
      ctx.log(iface_->watchdog().state() == DbwState::active ? LogLevel::info : LogLevel::warn, out.state_change);
      ctx.status("dbw", dbw_state_name(iface_->watchdog().state()));
    }
    if (!bus_->send(out.frames)) device_failed(ctx);
    if (out.race_control_changed || now >= next_status_ns_)
      io_.race_control.publish(race_control_message(iface_->race_control(), now, race_seq_++));
    if (changed || now >= next_status_ns_) publish_status(now), next_status_ns_ = now + status_period_ns_;
  }

  void deactivate(Context& ctx) override {
    if (!iface_) return;
    report_interface(ctx, *iface_, bus_->counts());
    report_race_control(ctx, iface_->race_control(), race_bus_ ? &race_bus_->counts() : nullptr);
  }

 private:
  void warn(Context& ctx, const std::string& what) { ctx.log(LogLevel::warn, what); }

  void device_failed(Context& ctx) {
    const std::string& why = bus_->error().empty() && race_bus_ ? race_bus_->error() : bus_->error();
    if (!bus_error_logged_) ctx.log(LogLevel::error, "bus " + why + ": no more frames to or from the car");
    bus_error_logged_ = true;
  }

  void publish_speeds(std::int64_t now) {
    const DbwReports& r = iface_->reports();
    msgs::WheelSpeeds m;
    m.header().stamp_ns(now);
    m.header().seq(speeds_seq_++);
    m.header().frame_id("vehicle");
    m.front_left(r.wheel_fl), m.front_right(r.wheel_fr), m.rear_left(r.wheel_rl), m.rear_right(r.wheel_rr);
    io_.speeds.publish(std::move(m));
  }

  void publish_status(std::int64_t now) { io_.status.publish(status_message(*iface_, now, status_seq_++)); }

  std::optional<RaptorInterface> iface_;
  std::unique_ptr<CanBus> bus_, race_bus_;
  std::vector<CanFrame> frames_;
  Ports io_;
  std::uint64_t wheel_reports_ = 0;
  std::uint32_t speeds_seq_ = 0, status_seq_ = 0, race_seq_ = 0;
  std::int64_t status_period_ns_ = 0, next_status_ns_ = 0;
  bool bus_error_logged_ = false;
};

}  // namespace

BRICKYARD_PLUGINS(RaptorDbw)
