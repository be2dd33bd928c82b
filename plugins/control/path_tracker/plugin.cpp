// control.path_tracker: follows a Path (pure pursuit with a speed-scheduled look-ahead, speed
// braking ahead of slower stretches; common/path_tracker.hpp) from the localization estimate.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/plugin.hpp>

#include "../command_msg.hpp"
#include "vehicle_param.hpp"
#include "common/path_tracker.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::control;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  TrackerParams tracker;  // its wheelbase comes from the vehicle file
};

ParamBinding<Settings> bindings() {
  using T = TrackerParams;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: the wheelbase pure pursuit steers with");
  b.bind("lookahead_min", &Settings::tracker, &T::lookahead_min).in_unit("m").at_least(0.5);
  b.bind("lookahead_time", &Settings::tracker, &T::lookahead_time).in_unit("s").at_least(0).doc("look-ahead = this x speed, clamped");
  b.bind("lookahead_max", &Settings::tracker, &T::lookahead_max).in_unit("m").at_least(0.5);
  b.bind("max_steer", &Settings::tracker, &T::max_steer).in_unit("rad").at_least(0.01);
  b.bind("speed_gain", &Settings::tracker, &T::speed_gain).at_least(0).doc("pedal per m/s of speed error");
  b.bind("preview_time", &Settings::tracker, &T::preview_time).in_unit("s").at_least(0).doc("path ahead the speed looks at");
  b.bind("decel", &Settings::tracker, &T::decel).in_unit("m/s^2").at_least(0.1).doc("braking the speed plan assumes");
  b.bind("closed", &Settings::tracker, &T::closed)
      .doc("the path may be a loop: it is one when its end lies within two of its longest steps of its start (a racing line); false: always open");
  b.not_above("lookahead_min", "lookahead_max");
  return b;
}

class PathTrackerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("control.path_tracker", "1.0.0")
        .describe("pure pursuit on the path with a speed-scheduled look-ahead; speed from the path, braking ahead of slower stretches")
        .input<msgs::Path>("path", "the path to follow (the newest replaces the last)", true, 2)
        .input<msgs::LocalizationEstimate>("estimate", "where the car is: x, y, yaw, speed of base_link", true, 8)
        .output<msgs::ControlCommand>("command", "steer and pedals, source \"path_tracker\"")
        .parameters(bindings())
        .on_input("estimate");
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    TrackerParams tp = s.tracker;
    tp.wheelbase = plugins::read_vehicle(ctx, s.vehicle).wheelbase;
    tracker_ = PathTracker(tp);
    path_ = ctx.input<msgs::Path>("path");
    estimate_ = ctx.input<msgs::LocalizationEstimate>("estimate");
    out_ = ctx.output<msgs::ControlCommand>("command");
  }

  void step(Context& ctx) override {
    auto paths = path_.take();
    if (!paths.empty()) {
      const msgs::Path& m = *paths.back();
      std::vector<PathPoint> pts;
      const std::size_t n = m.poses().size();
      for (std::size_t i = 0; i < n; ++i)
        pts.push_back({m.poses()[i].x(), m.poses()[i].y(), i < m.speed().size() ? m.speed()[i] : 0.0});
      tracker_.set_path(std::move(pts));
      ++paths_;
    }
    for (auto& e : estimate_.take()) {
      const Command c = tracker_.control(e->x(), e->y(), e->yaw(), e->speed());
      out_.publish(command_message(c, "path_tracker", e->header().stamp_ns(), seq_++));
      cte_max_ = std::max(cte_max_, std::abs(tracker_.cross_track()));
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("commands", static_cast<double>(seq_));
    ctx.metric("paths", static_cast<double>(paths_));
    ctx.metric("max_cross_track_m", cte_max_);
  }

 private:
  PathTracker tracker_;
  Input<msgs::Path> path_;
  Input<msgs::LocalizationEstimate> estimate_;
  Output<msgs::ControlCommand> out_;
  std::uint32_t seq_ = 0;
  std::uint64_t paths_ = 0;
  double cte_max_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(PathTrackerNode)
