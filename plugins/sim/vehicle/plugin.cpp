// sim.vehicle: the race car. Integrates the dynamic single-track model at rate_hz on the road of
// the world it is given and publishes the ground truth every step.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include <cmath>

#include "vehicle_param.hpp"

#include "../common/command_watchdog.hpp"
#include "../common/vehicle_model.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  double rate_hz = 500;  // the trigger's rate, and 1 / rate_hz the integration step
  double start_s = 0, start_d = 0, start_speed = 0;
  std::string vehicle = plugins::default_vehicle_file;
  CommandWatchdogParams watchdog;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(100, 10000).doc("integration rate");
  b.bind("start_s", &Settings::start_s).in_unit("m").range(-1e5, 1e5).doc("start position along the centre line");
  b.bind("start_d", &Settings::start_d).in_unit("m").range(-100, 100).doc("start lateral offset, left positive");
  b.bind("start_speed", &Settings::start_speed).in_unit("m/s").range(0, 200);
  plugins::bind_vehicle(b, &Settings::vehicle);
  using W = CommandWatchdogParams;
  b.bind("command_timeout", &Settings::watchdog, &W::timeout_s).in_unit("s").range(0.01, 3600)
      .doc("commands stale this long (once they have come): throttle off, brake to a stop (the command watchdog)");
  b.bind("first_command_timeout", &Settings::watchdog, &W::first_timeout_s).in_unit("s").range(0.01, 3600)
      .doc("no command this long after the car exists: the same");
  b.bind("watchdog_brake", &Settings::watchdog, &W::brake).range(0, 1).doc("the brake pedal while the watchdog stops the car");
  return b;
}

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
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const VehicleParams v = plugins::read_vehicle(ctx, s.vehicle);
    model_ = std::make_unique<VehicleModel>(v);
    dt_ = 1.0 / s.rate_hz;
    start_s_ = s.start_s;
    start_d_ = s.start_d;
    start_speed_ = s.start_speed;
    watchdog_ = CommandWatchdog(s.watchdog);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!track_) {
      auto w = newest(io_.world);
      if (!w) return;  // no world yet: the car does not exist
      track_ = std::make_unique<Track>(from_message(*w));
      Frenet f = track_->at(start_s_, start_d_);
      Eigen::Vector2d base = track_->position(f);
      double yaw = track_->heading(f);
      auto& s = model_->state();
      s.yaw = yaw;
      s.x = base.x() + model_->params().lr * std::cos(yaw);
      s.y = base.y() + model_->params().lr * std::sin(yaw);
      s.vx = start_speed_;
      hint_ = f.seg;
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
      const bool was = watchdog_.stopping();
      c = watchdog_.apply(ctx.now_s(), !fresh.empty(), c);
      if (watchdog_.stopping() && !was)
        ctx.log(LogLevel::warn, "no command for " + std::to_string(ctx.now_s() - watchdog_.quiet_since()) + " s: throttle off, braking to a stop");
      if (was && !watchdog_.stopping())
        ctx.log(LogLevel::warn, "commands again: the stack drives (the longest gap between two so far: " + std::to_string(watchdog_.longest_gap()) + " s)");
    }
    const auto& s = model_->state();
    Frenet f = track_->project(s.x, s.y, hint_);
    model_->step(dt_, c, track_->road_gradient(f));
    if (!std::isfinite(s.x) || !std::isfinite(s.vx)) throw std::runtime_error("vehicle state is not finite");
    publish(ctx);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("command_watchdog_trips", static_cast<double>(watchdog_.trips()));
    ctx.metric("longest_command_gap_s", watchdog_.longest_gap());
    if (model_) ctx.metric("final_speed_mps", model_->state().vx);
  }

 private:
  void publish(Context& ctx) {
    const auto& s = model_->state();
    const double lr = model_->params().lr, c = std::cos(s.yaw), sn = std::sin(s.yaw);
    const double bx = s.x - lr * c, by = s.y - lr * sn;
    Frenet f = track_->project(bx, by, hint_);
    hint_ = f.seg;
    Eigen::Vector2d g = track_->road_gradient(f);
    msgs::VehicleState m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.header().frame_id("map");
    m.x(bx);
    m.y(by);
    m.z(track_->road_z(f));
    m.yaw(s.yaw);
    m.pitch(-std::atan(g.x() * c + g.y() * sn));
    m.roll(std::atan(-g.x() * sn + g.y() * c));
    m.vx(s.vx);
    m.vy(s.vy - lr * s.r);
    m.yaw_rate(s.r);
    m.ax(s.ax);
    m.ay(s.ay);
    m.steer(s.steer);
    m.s(f.s);
    m.d(f.d);
    io_.truth.publish(std::move(m));
  }

  std::unique_ptr<VehicleModel> model_;
  std::unique_ptr<Track> track_;
  CommandWatchdog watchdog_;
  double dt_ = 0.002, start_s_ = 0, start_d_ = 0, start_speed_ = 0;
  int hint_ = -1;
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(Vehicle)
