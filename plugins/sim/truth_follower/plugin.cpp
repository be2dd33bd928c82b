// sim.truth_follower: drives the simulated car from ground truth (pure pursuit on a racing line
// with a speed profile), so graphs can drive before the real estimation and control stack.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"

#include "control/path_tracker.hpp"
#include "control/vehicle_tracking.hpp"
#include "motion/racing_line.hpp"
#include "motion/vehicle_limits.hpp"

#include <cmath>
#include "tracker_params.hpp"
#include "../world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

// The driver's own defaults: a look-ahead a little longer than the car stack's tracker.
control::TrackerParams driver_defaults() {
  control::TrackerParams t;
  t.lookahead_min = 12;
  return t;
}

struct Settings {
  std::string raceline = "racelines/IMS.csv";
  motion::VehicleLimits limits;  // v_max and the accelerations bound; independent_limits() sets the rest
  bool vehicle_limits = false;   // true: the vehicle file's envelope instead (ellipse, drag, power)
  double grip_use = 0.93;        // with it: the share of its lateral grip the profile plans with
  double curvature_smooth_m = 30;
  double edge_margin = 2.5;
  control::TrackerParams tracker = driver_defaults();  // the car's facts come from its file
  std::string vehicle = plugins::default_vehicle_file;
};

ParamBinding<Settings> bindings() {
  using L = motion::VehicleLimits;
  ParamBinding<Settings> b;
  b.bind("raceline", &Settings::raceline).doc("x_m,y_m file of the line to follow");
  b.declare(ParamSpec::number("rate_hz", 100).in_unit("Hz").range(1, 1000));  // the host's trigger only
  b.bind("v_max", &Settings::limits, &L::v_max).in_unit("m/s").range(1, 200);
  b.bind("a_lat", &Settings::limits, &L::a_lat).in_unit("m/s^2").range(0.5, 100);
  b.bind("a_accel", &Settings::limits, &L::a_accel).in_unit("m/s^2").range(0.1, 100);
  b.bind("a_decel", &Settings::limits, &L::a_decel).in_unit("m/s^2").range(0.1, 100);
  b.bind_choice("profile_limits", {{"graph", false}, {"vehicle", true}}, &Settings::vehicle_limits)
      .doc("the speed profile's limits: graph (v_max, a_lat, a_accel, a_decel, each on its own) or vehicle (the vehicle file's: the ellipse, drag and power)");
  b.bind("grip_use", &Settings::grip_use).range(0.1, 1)
      .doc("profile_limits vehicle: the share of the file's lateral acceleration planned with (a margin for transients)");
  b.bind("curvature_smooth_m", &Settings::curvature_smooth_m).in_unit("m").range(0, 200)
      .doc("the profile reads the line's curvature averaged over this (30: as the planners; less for chicanes)");
  b.bind("edge_margin", &Settings::edge_margin).in_unit("m").range(0, 100)
      .doc("closest the line's points may come to a track edge (needs the world input)");
  plugins::bind_tracker(b, &Settings::tracker);
  plugins::bind_vehicle(b, &Settings::vehicle);
  return b;
}

struct Ports {
  Input<msgs::VehicleState> truth;
  Input<msgs::TrackWorld> world;
  Output<msgs::ControlCommand> command;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("truth", &Ports::truth).doc("ground truth").depth(1);
  b.input("world", &Ports::world).doc("when wired, the line is kept edge_margin inside the track").optional().depth(1);
  b.output("command", &Ports::command).doc("steer, throttle, brake");
  return b;
}

class TruthFollower : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.truth_follower", "1.0.0")
        .describe("Drives a racing line from ground truth with the car stack's path tracker (libs/control): a stand-in driver for simulator graphs")
        .with_ports(ports())
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
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, s.vehicle);
    const motion::VehicleLimits& l = s.limits;
    limits_ = motion::independent_limits(l.v_max, l.a_lat, l.a_accel, l.a_decel);
    if (s.vehicle_limits) {
      limits_ = motion::vehicle_limits(car);
      limits_.a_lat *= s.grip_use;
    }
    smooth_m_ = s.curvature_smooth_m;
    tracker_params_ = s.tracker;
    control::apply_vehicle(tracker_params_, car);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!tracker_) {
      // With a world wired, wait for it and keep the line inside the track; without, use the file.
      CenterLine line = line_;
      if (io_.world.connected()) {
        auto w = newest(io_.world);
        if (!w) return;
        Track t(from_message(*w));
        line = motion::keep_inside(line_, t, margin_);
      }
      const motion::RacingLine r = motion::make_racing_line(line, limits_, smooth_m_);
      std::vector<control::PathPoint> pts;
      for (std::size_t i = 0; i < r.x.size(); ++i) pts.push_back({r.x[i], r.y[i], r.speed[i]});
      tracker_ = std::make_unique<control::PathTracker>(tracker_params_);
      tracker_->set_path(std::move(pts));
      // The lap the profile plans: what a driven lap is measured against (docs/control.md).
      std::vector<double> ds(r.x.size());
      for (std::size_t i = 0; i < r.x.size(); ++i) {
        const std::size_t j = (i + 1) % r.x.size();
        ds[i] = std::hypot(r.x[j] - r.x[i], r.y[j] - r.y[i]);
      }
      ctx.metric("planned_lap_s", motion::profile_time(ds, r.speed, true));
      ctx.metric("line_length_m", r.length);
    }
    auto s = newest(io_.truth);
    if (!s) return;
    const motion::Command c = tracker_->control(control::CarState{s->x(), s->y(), s->yaw(), s->vx(), s->yaw_rate(), s->vy()});
    const double target = c.target_speed;
    msgs::ControlCommand m;
    m.header().stamp_ns(ctx.now_ns());
    m.header().seq(seq_++);
    m.steer(c.steer);
    m.throttle(c.throttle);
    m.brake(c.brake);
    m.target_speed(target);
    m.source("truth_follower");
    io_.command.publish(std::move(m));
  }

 private:
  CenterLine line_;
  double margin_ = 2.5, smooth_m_ = 30;
  motion::VehicleLimits limits_;
  control::TrackerParams tracker_params_;
  std::unique_ptr<control::PathTracker> tracker_;
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(TruthFollower)
