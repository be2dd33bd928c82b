// sim.wheels: four wheel speeds (linear speed at the tyre) from the ground truth, with a scale
// error (tyre radius), noise and fault windows.
#include <brickyard/msgs/WheelSpeeds.h>
#include <brickyard/plugin.hpp>

#include <cmath>

#include "vehicle_param.hpp"
#include "sim/common/digest.hpp"
#include "sim/common/rng.hpp"
#include "sim/sensor_faults.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// The fault windows wheel speed sensors take, over (fl, fr, rl, rr).
const std::vector<std::string> kFaultTypes = {"bias", "drift", "noise", "freeze", "dropout", "spikes"};

struct Settings {
  double noise = 0.05, scale = 1.0;
  std::string vehicle = plugins::default_vehicle_file;
  FaultSchedule faults{"[]", 4, kFaultTypes};  // as declared: no window
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.declare(ParamSpec::number("rate_hz", 100).in_unit("Hz").range(1, 10000));  // the host's trigger only
  b.bind("noise", &Settings::noise).in_unit("m/s").range(0, 100);
  b.bind("scale", &Settings::scale).range(0.5, 2).doc("tyre radius error as a factor");
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: wheelbase and track width");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]")
                  .doc("windows over (fl, fr, rl, rr): bias, drift, noise, freeze, dropout, spikes"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 4, kFaultTypes); });
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Output<msgs::WheelSpeeds> speeds;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(1);
  b.output("speeds", &Ports::speeds).doc("m/s at the tyre");
  return b;
}

class Wheels : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.wheels", "1.0.0")
        .describe("Wheel speed sensors: speed of each wheel centre along the wheel's heading, with noise and faults")
        .with_ports(ports())
        .plays(roles::wheel_speed_driver)
        .parameters(bindings())
        .check(&plugins::check_vehicle_file<&bindings, &Settings::vehicle>)
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    noise_ = s.noise;
    scale_ = s.scale;
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    wb_ = car.wheelbase;
    half_track_ = car.track_width / 2;
    faults_ = s.faults;
    rng_ = Rng(ctx.seed());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    auto s = newest(io_.truth);
    if (!s) return;
    double n[4];
    for (double& v : n) v = rng_.normal();
    FaultEffect e = faults_.at(run_.now_s(ctx), rng_);
    if (e.drop) return;
    msgs::WheelSpeeds m;
    if (e.freeze && last_) {
      m = *last_;
    } else {
      // Wheel-centre velocity = base_link velocity + yaw rate x lever arm; fronts are steered.
      const double vx = s->vx(), vy = s->vy(), r = s->yaw_rate(), d = s->steer();
      auto along = [&](double lx, double ly, double heading) {
        double wx = vx - r * ly, wy = vy + r * lx;
        return wx * std::cos(heading) + wy * std::sin(heading);
      };
      const double truth[4] = {along(wb_, half_track_, d), along(wb_, -half_track_, d), along(0, half_track_, 0),
                               along(0, -half_track_, 0)};
      double v[4];
      for (int i = 0; i < 4; ++i) v[i] = scale_ * truth[i] + e.offset[i] + noise_ * e.noise_factor * n[i];
      m.front_left(v[0]); m.front_right(v[1]); m.rear_left(v[2]); m.rear_right(v[3]);
    }
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.header().frame_id("vehicle");
    for (double v : {m.front_left(), m.front_right(), m.rear_left(), m.rear_right()}) digest_.add(v);
    last_ = std::make_shared<msgs::WheelSpeeds>(m);
    io_.speeds.publish(std::move(m));
  }

  void deactivate(Context& ctx) override { ctx.metric("digest", digest_.hex()); }

 private:
  Digest digest_;
  double noise_ = 0, scale_ = 1, wb_ = 0, half_track_ = 0;
  FaultSchedule faults_;
  Rng rng_;
  std::uint32_t seq_ = 0;
  std::shared_ptr<msgs::WheelSpeeds> last_;
  Ports io_;
  RunTime run_;
};

}  // namespace

BRICKYARD_PLUGINS(Wheels)
