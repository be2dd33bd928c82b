// sim.truth_follower: drives the simulated car from ground truth (pure pursuit on a racing line
// with a speed profile), so graphs can drive before the real estimation and control stack.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"

#include "../common/pure_pursuit.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::string raceline = "racelines/IMS.csv";
  motion::VehicleLimits limits;  // v_max and the accelerations bound; independent_limits() sets the rest
  double edge_margin = 2.5;
  PursuitParams pursuit;  // the look-ahead and the speed gain; the car's facts come from its file
  std::string vehicle = plugins::default_vehicle_file;
};

ParamBinding<Settings> bindings() {
  using L = motion::VehicleLimits;
  using P = PursuitParams;
  ParamBinding<Settings> b;
  b.bind("raceline", &Settings::raceline).doc("x_m,y_m file of the line to follow");
  b.declare(ParamSpec::number("rate_hz", 100).in_unit("Hz").at_least(1));  // the host's trigger only
  b.bind("v_max", &Settings::limits, &L::v_max).in_unit("m/s").at_least(1);
  b.bind("a_lat", &Settings::limits, &L::a_lat).in_unit("m/s^2").at_least(0.5);
  b.bind("a_accel", &Settings::limits, &L::a_accel).in_unit("m/s^2").at_least(0.1);
  b.bind("a_decel", &Settings::limits, &L::a_decel).in_unit("m/s^2").at_least(0.1);
  b.bind("edge_margin", &Settings::edge_margin).in_unit("m").at_least(0)
      .doc("closest the line's points may come to a track edge (needs the world input)");
  b.bind("lookahead_min", &Settings::pursuit, &P::lookahead_min).in_unit("m").at_least(0.5);
  b.bind("lookahead_time", &Settings::pursuit, &P::lookahead_time).in_unit("s").at_least(0);
  b.bind("speed_gain", &Settings::pursuit, &P::speed_gain).at_least(0);
  plugins::bind_vehicle(b, &Settings::vehicle);
  return b;
}

class TruthFollower : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.truth_follower", "1.0.0")
        .describe("Pure pursuit on a racing line from ground truth (a stand-in driver for simulator graphs)")
        .input<msgs::VehicleState>("truth", "ground truth", true, 1)
        .input<msgs::TrackWorld>("world", "when wired, the line is kept edge_margin inside the track", false, 1)
        .output<msgs::ControlCommand>("command", "steer, throttle, brake")
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const std::string path = ctx.find_file(s.raceline);
    CenterLine xy;
    try {
      xy = load_xy_csv(path);
    } catch (const TrackFileError& e) {
      throw BadInput(std::string("raceline file ") + e.what());
    }
    line_ = xy;
    margin_ = s.edge_margin;
    const motion::VehicleLimits& l = s.limits;
    limits_ = motion::independent_limits(l.v_max, l.a_lat, l.a_accel, l.a_decel);
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    pursuit_params_ = s.pursuit;
    pursuit_params_.wheelbase = car.wheelbase;
    pursuit_params_.max_steer = car.max_steer;
    world_ = ctx.input<msgs::TrackWorld>("world");
    truth_ = ctx.input<msgs::VehicleState>("truth");
    out_ = ctx.output<msgs::ControlCommand>("command");
  }

  void step(Context& ctx) override {
    if (!pursuit_) {
      // With a world wired, wait for it and keep the line inside the track; without, use the file.
      CenterLine line = line_;
      if (world_.connected()) {
        auto w = newest(world_);
        if (!w) return;
        Track t(from_message(*w));
        line = motion::keep_inside(line_, t, margin_);
      }
      pursuit_ = std::make_unique<PurePursuit>(motion::make_racing_line(line, limits_), pursuit_params_);
    }
    auto s = newest(truth_);
    if (!s) return;
    double target = 0;
    Command c = pursuit_->control(s->x(), s->y(), s->yaw(), s->vx(), &target);
    msgs::ControlCommand m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.steer(c.steer);
    m.throttle(c.throttle);
    m.brake(c.brake);
    m.target_speed(target);
    m.source("truth_follower");
    out_.publish(std::move(m));
  }

 private:
  CenterLine line_;
  double margin_ = 2.5;
  motion::VehicleLimits limits_;
  PursuitParams pursuit_params_;
  std::unique_ptr<PurePursuit> pursuit_;
  Input<msgs::TrackWorld> world_;
  std::uint32_t seq_ = 0;
  Input<msgs::VehicleState> truth_;
  Output<msgs::ControlCommand> out_;
};

}  // namespace

BRICKYARD_PLUGINS(TruthFollower)
