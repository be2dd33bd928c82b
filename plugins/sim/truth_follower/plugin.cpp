// sim.truth_follower: drives the simulated car from ground truth (pure pursuit on a racing line
// with a speed profile), so graphs can drive before the real estimation and control stack.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"

#include "control/path_tracker.hpp"
#include "control/vehicle_tracking.hpp"

#include "tracker_params.hpp"
#include "sim/common/driver_line.hpp"
#include "sim/world_msg.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  std::string raceline = "racelines/IMS.csv";
  DriverProfile profile;
  control::TrackerParams tracker = driver_tracker_defaults();  // the car's facts come from its file
  std::string vehicle = plugins::default_vehicle_file;
};

ParamBinding<Settings> bindings() {
  using L = motion::VehicleLimits;
  using P = DriverProfile;
  ParamBinding<Settings> b;
  b.bind("raceline", &Settings::raceline).doc("x_m,y_m file of the line to follow");
  b.declare(ParamSpec::number("rate_hz", 100).in_unit("Hz").range(1, 1000));  // the host's trigger only
  b.bind("v_max", &Settings::profile, &P::limits, &L::v_max).in_unit("m/s").range(1, 200);
  b.bind("a_lat", &Settings::profile, &P::limits, &L::a_lat).in_unit("m/s^2").range(0.5, 100);
  b.bind("a_accel", &Settings::profile, &P::limits, &L::a_accel).in_unit("m/s^2").range(0.1, 100);
  b.bind("a_decel", &Settings::profile, &P::limits, &L::a_decel).in_unit("m/s^2").range(0.1, 100);
  b.bind_choice("profile_limits", {{"graph", false}, {"vehicle", true}}, &Settings::profile, &P::vehicle_limits)
      .doc("the speed profile's limits: graph (v_max, a_lat, a_accel, a_decel, each on its own) or vehicle (the vehicle file's: the ellipse, drag and power)");
  b.bind("grip_use", &Settings::profile, &P::grip_use).range(0.1, 1)
      .doc("profile_limits vehicle: the share of the file's lateral acceleration planned with (a margin for transients)");
  b.bind("curvature_smooth_m", &Settings::profile, &P::curvature_smooth_m).in_unit("m").range(0, 200)
      .doc("the profile reads the line's curvature averaged over this (30: as the planners; less for chicanes)");
  b.bind("edge_margin", &Settings::profile, &P::edge_margin).in_unit("m").range(0, 100)
      .doc("closest the line's points may come to a track edge (needs the world input)");
  b.bind("speed_scale", &Settings::profile, &P::speed_scale).range(0.05, 1.5).doc("the profile's speeds times this (a rival's pace)");
  b.bind("lateral_offset", &Settings::profile, &P::lateral_offset).in_unit("m").range(-30, 30).doc("the line moved across, left positive");
  plugins::bind_tracker(b, &Settings::tracker);
  plugins::bind_vehicle(b, &Settings::vehicle);
  return b;
}

// The files the settings name, read for configure and at validation (Manifest::check).
template <class Files> std::pair<CenterLine, vehicle::Vehicle> read_files(const Files& files, const Settings& s) {
  try {
    return {load_xy_csv(files.find_file(s.raceline)), plugins::read_vehicle_file(files.find_file(s.vehicle))};
  } catch (const TrackFileError& e) {
    throw BadInput(std::string("raceline file ") + e.what());
  }
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
        .periodic("rate_hz")
        .check(&check);
  }

  static void check(const CheckView& v) {
    const Settings s = bindings().read(v.params());
    plugins::tracker_for(s.tracker, read_files(v, s).second, s.vehicle);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    auto [line, car] = read_files(ctx, s);
    line_ = std::move(line);
    profile_ = s.profile;
    limits_ = profile_limits(profile_, car);
    tracker_params_ = plugins::tracker_for(s.tracker, car, s.vehicle);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!tracker_ && !start_driving(ctx)) return;
    auto s = newest(io_.truth);
    if (!s) return;
    const motion::Command c = tracker_->control(control::CarState{s->x(), s->y(), s->yaw(), s->vx(), s->yaw_rate(), s->vy(), 1e-9 * static_cast<double>(s->header().stamp_ns())});
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
  // The tracker on the line. With a world wired, wait for it (false) and keep the line inside the
  // track; without, the file's line.
  bool start_driving(Context& ctx) {
    std::unique_ptr<Track> track;
    if (io_.world.connected()) {
      auto w = newest(io_.world);
      if (!w) return false;
      track = std::make_unique<Track>(from_message(*w));
    }
    const DriverLine d = driver_line(line_, track.get(), profile_, limits_);
    std::vector<control::PathPoint> pts;
    for (std::size_t i = 0; i < d.line.x.size(); ++i) pts.push_back({d.line.x[i], d.line.y[i], d.line.speed[i]});
    tracker_ = std::make_unique<control::PathTracker>(tracker_params_);
    tracker_->set_path(std::move(pts));
    ctx.metric("planned_lap_s", d.planned_lap_s);
    ctx.metric("line_length_m", d.line.length);
    return true;
  }

  CenterLine line_;
  DriverProfile profile_;
  motion::VehicleLimits limits_;
  control::TrackerParams tracker_params_;
  std::unique_ptr<control::PathTracker> tracker_;
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(TruthFollower)
