// vehicle_interface.raptor_dbw: the stack's ControlCommand to the car's drive-by-wire (New Eagle's
// Raptor on the AV-21) over CAN, from the car's DBC, and its reports back as WheelSpeeds and
// VehicleStatus, and race control's flags as RaceControl (acknowledged in ct_report). Each period
// the bus is read without blocking and the commands due are sent (common/raptor_interface.hpp:
// rates, rolling counters, the gear, the team's heartbeat, the command watchdog, race control).
// docs/vehicle-interface.md, docs/race-control.md.
#include <brickyard/plugin.hpp>

#include "map_msg.hpp"
#include "newest.hpp"
#include "tracker_messages.hpp"
#include "vehicle_interface/raptor_dbw/bus_messages.hpp"
#include "vehicle_interface/raptor_dbw/metrics.hpp"
#include "vehicle_interface/raptor_dbw/params.hpp"
#include "vehicle_interface/raptor_dbw/ports.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::vehicle_interface;

void check(const CheckView& v) { read_setup(v, bindings().read(v.params())); }

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
    io_ = ports().connect(ctx);
    if (s.stop_on_path && io_.path.connected() && io_.estimate.connected()) iface_->stop_on_path(PathStop(setup.stop_tracker, s.path_stop));
    status_period_ns_ = static_cast<std::int64_t>(1e9 / s.status_hz);
    if (s.frames != FramesOut::none) bus_log_.emplace(std::move(setup.database), s.frames == FramesOut::decoded);
    bus_name_ = s.bus;
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    for (const auto& c : io_.command.take())
      if (std::string why = iface_->command({c->steer(), c->throttle(), c->brake(), c->target_speed()}); !why.empty())
        if (iface_->counts().bad_commands <= 20) warn(ctx, "command refused: " + why);  // then only counted
    if (PathStop* stop = iface_->path_stop()) {
      for (const auto& p : io_.path.take()) stop->path(1e-9 * static_cast<double>(p->header().stamp_ns()), plugins::path_points(*p));
      for (const auto& e : io_.estimate.take()) stop->estimate(plugins::car_state(*e));
      for (const auto& m : io_.imu.take()) stop->gyro(1e-9 * static_cast<double>(m->header().stamp_ns()), m->gyro_z());
      if (const auto m = plugins::newest(io_.map); m && m != refused_map_ && !stop->has_map()) take_map(ctx, *stop, m);
    }
    frames_.clear();
    if (!bus_->poll(frames_) || (race_bus_ && !race_bus_->poll(frames_))) device_failed(ctx);
    if (bus_log_) bus_log_->add(frames_, now, false);
    for (const std::string& w : iface_->receive(frames_, now)) warn(ctx, w);
    const std::uint64_t wheel_reports = iface_->monitor().counts(RaptorMessage::wheel_speed_report).received;
    if (wheel_reports != wheel_reports_) io_.speeds.publish(speeds_message(iface_->reports(), now, speeds_seq_++)), wheel_reports_ = wheel_reports;
    const InterfaceStep out = iface_->step(now);
    for (const std::string& w : out.warnings) warn(ctx, w);
    for (const std::string& n : out.notes) ctx.log(LogLevel::info, n);
    const bool changed = !out.state_change.empty();
    if (changed) {
      ctx.log(iface_->watchdog().state() == DbwState::active ? LogLevel::info : LogLevel::warn, out.state_change);
      ctx.status("dbw", dbw_state_name(iface_->watchdog().state()));
    }
    if (!bus_->send(out.frames)) device_failed(ctx);
    publish_frames(out.frames, now);
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

  void publish_frames(const std::vector<CanFrame>& sent, std::int64_t now) {
    if (!bus_log_) return;
    bus_log_->add(sent, now, true);
    if (!bus_log_->frames().empty()) io_.frames.publish(can_frames_message(*bus_log_, bus_name_, now, frames_seq_++));
    bus_log_->clear();
  }

  // The track's first map (a map source republishes it); one that is no track is named once and
  // not tried again until another comes.
  void take_map(Context& ctx, PathStop& stop, const std::shared_ptr<const msgs::TrackMap>& m) {
    try {
      stop.map(track::Track(plugins::from_message(*m)));
      ctx.log(LogLevel::info, "the stop along the path keeps room to the edges of '" + m->name() + "'");
    } catch (const std::invalid_argument& e) {
      if (!refused_map_) warn(ctx, "map '" + m->name() + "' refused: " + e.what() + "; the stop follows the path as it is");
      refused_map_ = m;
    }
  }

  void publish_status(std::int64_t now) { io_.status.publish(status_message(*iface_, now, status_seq_++)); }

  std::optional<RaptorInterface> iface_;
  std::unique_ptr<CanBus> bus_, race_bus_;
  std::vector<CanFrame> frames_;
  Ports io_;
  std::uint64_t wheel_reports_ = 0;
  std::optional<BusLog> bus_log_;
  std::string bus_name_;
  std::uint32_t speeds_seq_ = 0, status_seq_ = 0, race_seq_ = 0, frames_seq_ = 0;
  std::int64_t status_period_ns_ = 0, next_status_ns_ = 0;
  bool bus_error_logged_ = false;
  std::shared_ptr<const msgs::TrackMap> refused_map_;
};

}  // namespace

BRICKYARD_PLUGINS(RaptorDbw)
