// control.path_tracker: follows a Path (pure pursuit with a speed-scheduled look-ahead, speed
// braking ahead of slower stretches; libs/control/path_tracker.hpp) from the localization estimate.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/plugin.hpp>

#include "control/command_msg.hpp"
#include "control/path_tracker.hpp"
#include "control/steering_activity.hpp"
#include "control/vehicle_tracking.hpp"
#include "tracker_messages.hpp"
#include "tracker_params.hpp"
#include "vehicle_param.hpp"

#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::control;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  TrackerParams tracker;         // the car's facts come from the vehicle file
  std::optional<double> max_steer;  // NaN: the vehicle file's
};

ParamBinding<Settings> bindings() {
  using T = TrackerParams;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle)
      .doc("the car's description file: wheelbase, steering, single-track model, powertrain and grip");
  plugins::bind_tracker(b, &Settings::tracker);
  b.bind("max_steer", &Settings::max_steer).in_unit("rad").range(0.01, 1.5).doc("steering limit; default: the vehicle file's");
  b.bind("closed", &Settings::tracker, &T::closed)
      .doc("the path may be a loop: it is one when its end lies within two of its longest steps of its start (a racing line); false: always open");
  return b;
}

struct Ports {
  Input<msgs::Path> path;
  Input<msgs::LocalizationEstimate> estimate;
  Output<msgs::ControlCommand> command;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("path", &Ports::path).doc("the path to follow (the newest replaces the last)").depth(2);
  b.input("estimate", &Ports::estimate).doc("where the car is: x, y, yaw, speed of base_link").depth(8).steps();
  b.output("command", &Ports::command).doc("steer and pedals, source \"path_tracker\"");
  return b;
}

class PathTrackerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.path_tracker", "1.0.0")
        .describe("follows the path: pure pursuit or the single-track model's LQR; speed from the path, braking ahead of slower stretches")
        .with_ports(ports())
        .plays(roles::path_tracker)
        .parameters(bindings())
        .check(&check);
  }

  static void check(const CheckView& v) {
    const Settings s = bindings().read(v.params());
    plugins::tracker_for(s.tracker, plugins::read_vehicle_file(v.find_file(s.vehicle)), s.vehicle);
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    TrackerParams tp = plugins::tracker_for(s.tracker, plugins::read_vehicle(ctx, s.vehicle), s.vehicle);
    if (s.max_steer) tp.max_steer = *s.max_steer;
    tracker_ = PathTracker(tp);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    auto paths = io_.path.take();
    if (!paths.empty()) {
      tracker_.set_path(plugins::path_points(*paths.back()));
      ++paths_;
    }
    for (auto& e : io_.estimate.take()) {
      const CarState car = plugins::car_state(*e);
      const double t = car.time;
      const Command c = tracker_.control(car);
      io_.command.publish(command_message(c, "path_tracker", e->header().stamp_ns(), seq_++));
      cte_max_ = std::max(cte_max_, std::abs(tracker_.cross_track()));
      steering_.add(t, c.steer);
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("commands", static_cast<double>(seq_));
    ctx.metric("paths", static_cast<double>(paths_));
    ctx.metric("max_cross_track_m", cte_max_);
    ctx.metric("steer_rate_rms_radps", steering_.rate_rms());
  }

 private:
  PathTracker tracker_;
  Ports io_;
  std::uint32_t seq_ = 0;
  std::uint64_t paths_ = 0;
  double cte_max_ = 0;
  SteeringActivity steering_;
};

}  // namespace

BRICKYARD_PLUGINS(PathTrackerNode)
