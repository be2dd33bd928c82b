// sim.drive_by_wire: the simulated car's drive-by-wire on its CAN bus (New Eagle's Raptor, as the
// car's DBC describes it). Each period it reads the command frames the vehicle interface sent
// (vehicle_interface.raptor_dbw, over cannelloni datagrams on UDP), gives sim.vehicle the command
// they make through the same maps, with its own safety stop when they or the heartbeat stop
// (common/drive_by_wire.hpp), and at report_hz sends the reports: wheel speeds from sim.wheels,
// the steering angle and speed from the truth, the brake and pedal it applies, the gear and rpm.
// docs/vehicle-interface.md.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include "sim/common/stop_meter.hpp"
#include "sim/drive_by_wire/metrics.hpp"
#include "sim/drive_by_wire/params.hpp"
#include "sim/run_time.hpp"
#include "sim/world_msg.hpp"

#include <cstdio>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::VehicleState> truth;
  Input<msgs::WheelSpeeds> wheels;
  Output<msgs::ControlCommand> command;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("the car: its steering angle and speed for the reports").depth(1);
  b.input("wheels", &Ports::wheels).doc("the wheel speed sensors (sim.wheels) for wheel_speed_report").depth(1);
  b.output("command", &Ports::command).doc("to sim.vehicle: what the command frames ask, or its own stop");
  return b;
}

class DriveByWire : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.drive_by_wire", "1.0.0")
        .describe("the simulated car's drive-by-wire on its CAN bus: command frames in (counters, its own timeout), sim.vehicle's command out, reports back")
        .with_ports(ports())
        .parameters(bindings())
        .check(&check)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    vehicle::Vehicle car;
    dbw_.emplace(vi::read_mapping(ctx, s.dbc, s.vehicle, car), s.dbw, ctx.seed());
    std::string error;
    bus_ = vi::open_bus(bus_of(s), error);
    if (!bus_) throw BadInput("parameter 'bus': " + error);
    report_period_ns_ = static_cast<std::int64_t>(1e9 / s.report_hz);
    faults_ = s.faults;
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    frames_.clear();
    if (!bus_->poll(frames_)) failed(ctx);
    const double t = faults_.empty() ? 0 : run_.now_s(ctx);
    const bool deaf = bus_fault(faults_, "deaf", t), mute = bus_fault(faults_, "mute", t);
    if (deaf) frames_unheard_ += frames_.size(), frames_.clear();
    dbw_->receive(frames_, now);
    const bool was_stopping = dbw_->stopping();
    const motion::Command c = dbw_->command(now);
    if (dbw_->stopping() != was_stopping)
      ctx.log(LogLevel::warn, dbw_->stopping() ? "drive-by-wire: commands or heartbeat lost: braking" : "drive-by-wire: commands back");
    measure_stop(ctx, was_stopping);
    publish(c, now);
    if (now < next_report_ns_) return;
    next_report_ns_ = now + report_period_ns_;
    std::vector<vi::CanFrame> reports = dbw_->reports(reading());
    if (mute) reports_unsent_ += reports.size(), reports.clear();
    if (!bus_->send(reports)) failed(ctx);
  }

  void deactivate(Context& ctx) override {
    if (!dbw_) return;
    report_metrics(ctx, *dbw_, stop_);
    if (!faults_.empty()) ctx.metric("frames_unheard", frames_unheard_), ctx.metric("reports_unsent", reports_unsent_);
  }

 private:
  SimCarReading reading() {
    SimCarReading r;
    if (const auto t = newest(io_.truth)) r.steer = t->steer(), r.speed = t->vx();
    if (const auto w = newest(io_.wheels))
      r.wheel_fl = w->front_left(), r.wheel_fr = w->front_right(), r.wheel_rl = w->rear_left(), r.wheel_rr = w->rear_right();
    return r;
  }

  // Its own stop measured from the car's truth: from the speed it began at to standstill.
  void measure_stop(Context& ctx, bool was_stopping) {
    const auto t = newest(io_.truth);
    if (!t) return;
    const double at = static_cast<double>(stamp(*t)) * 1e-9;
    if (dbw_->stopping() && !was_stopping) stop_.begin(at, t->vx());
    else if (!dbw_->stopping() && was_stopping) stop_.abandon();
    else stop_.sample(at, t->vx());
    if (stop_.stood() && !stood_said_) {
      char b[96];
      std::snprintf(b, sizeof b, "drive-by-wire: stopped from %.1f m/s in %.1f m", stop_.from_speed_mps(), stop_.distance_m());
      ctx.log(LogLevel::info, b);
      stood_said_ = true;
    }
    if (stop_.measuring()) stood_said_ = false;
  }

  void publish(const motion::Command& c, std::int64_t now) {
    msgs::ControlCommand m;
    m.header().stamp_ns(now);
    m.header().seq(seq_++);
    m.header().frame_id("vehicle");
    m.steer(c.steer), m.throttle(c.throttle), m.brake(c.brake);
    m.source(dbw_->stopping() ? "drive_by_wire_stop" : "drive_by_wire");
    io_.command.publish(std::move(m));
  }

  void failed(Context& ctx) {
    if (!error_logged_) ctx.log(LogLevel::error, "bus " + bus_->error());
    error_logged_ = true;
  }

  std::optional<SimDriveByWire> dbw_;
  FaultSchedule faults_;
  RunTime run_;
  std::uint64_t frames_unheard_ = 0, reports_unsent_ = 0;
  StopMeter stop_;
  bool stood_said_ = false;
  std::unique_ptr<vi::CanBus> bus_;
  std::vector<vi::CanFrame> frames_;
  Ports io_;
  std::int64_t report_period_ns_ = 0, next_report_ns_ = 0;
  std::uint32_t seq_ = 0;
  bool error_logged_ = false;
};

}  // namespace

BRICKYARD_PLUGINS(DriveByWire)
