// sim.vehicle: the race car. Integrates the dynamic single-track model at rate_hz on the road of
// the world it is given and publishes the ground truth every step; on the real clock each step
// integrates the time since the last (common/step_span.hpp), so the car keeps the wall's time.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include <optional>

#include "vehicle_settings.hpp"

#include "sim/common/car_on_track.hpp"
#include "sim/common/step_span.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::ControlCommand> command;
  Output<msgs::VehicleState> truth;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world to drive in").depth(1);
  b.input("command", &Ports::command)
      .doc("steer, throttle, brake (the latest holds until it is command_timeout old: then the car brakes to a stop)")
      .optional()
      .depth(1);
  b.output("truth", &Ports::truth).doc("ground truth at base_link (rear-axle centre), every step");
  return b;
}

class Vehicle : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.vehicle", "1.0.0")
        .describe("Dynamic single-track race car (the vehicle file's, AV-21 by default) on the world's banked road; publishes ground truth")
        .with_ports(ports())
        .plays(roles::vehicle_interface)
        .parameters(vehicle_bindings())
        .check(&check_start)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const VehicleSettings s = vehicle_bindings().read(ctx.params());
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    half_width_ = car.half_width;
    car_.emplace(car);
    dt_ = 1.0 / s.rate_hz;
    start_s_ = s.start_s;
    start_d_ = s.start_d;
    start_speed_ = s.start_speed;
    watchdog_ = CommandWatchdog(s.watchdog);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!car_->placed()) {
      auto w = newest(io_.world);
      if (!w) return;  // no world yet: the car does not exist
      track_ = std::make_unique<Track>(from_message(*w));
      if (const std::string off = off_the_road(*track_, start_s_, start_d_, half_width_); !off.empty())
        throw BadInput("parameter 'start_d': " + off);
      car_->place(*track_, start_s_, start_d_, start_speed_);
      last_step_s_ = ctx.now_s();
      publish(ctx);
      return;
    }
    Command c;
    auto fresh = io_.command.take();
    if (auto m = fresh.empty() ? io_.command.latest() : fresh.back()) {
      c.steer = m->steer();
      c.throttle = m->throttle();
      c.brake = m->brake();
    }
    // An unwired command input is a fixture (a car that coasts); a wired one is the stack's.
    if (io_.command.connected()) {
      const WatchedCommand w = watch_command(watchdog_, ctx.now_s(), !fresh.empty(), c);
      c = w.command;
      if (!w.warning.empty()) ctx.log(LogLevel::warn, w.warning);
    }
    const StepSpan span = ctx.sim_clock() ? StepSpan{1, dt_} : real_clock_span(ctx.now_s() - last_step_s_, dt_);
    for (int i = 0; i < span.steps; ++i) car_->step(span.dt, c);
    last_step_s_ = ctx.now_s();
    publish(ctx);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("command_watchdog_trips", static_cast<double>(watchdog_.trips()));
    ctx.metric("longest_command_gap_s", watchdog_.longest_gap(ctx.now_s()));
    ctx.metric("last_command_s", watchdog_.last_command());
    if (car_) ctx.metric("final_speed_mps", car_->state().vx);
  }

 private:
  void publish(Context& ctx) {
    const BaseLinkTruth t = car_->truth();
    msgs::VehicleState m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.header().frame_id("map");
    m.x(t.x); m.y(t.y); m.z(t.z);
    m.yaw(t.yaw); m.pitch(t.pitch); m.roll(t.roll);
    m.vx(t.vx); m.vy(t.vy); m.yaw_rate(t.yaw_rate);
    m.ax(t.ax); m.ay(t.ay); m.steer(t.steer);
    m.s(t.s); m.d(t.d);
    io_.truth.publish(std::move(m));
  }

  std::optional<CarOnTrack> car_;
  std::unique_ptr<Track> track_;
  CommandWatchdog watchdog_;
  double dt_ = 0.002, start_s_ = 0, start_d_ = 0, start_speed_ = 0, half_width_ = 0;
  double last_step_s_ = 0;  // real clock: the physics is stepped up to here
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Vehicle)
