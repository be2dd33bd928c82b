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

class PathTrackerNode : public Plugin {
 public:
  static Manifest manifest() {
    const TrackerParams d;
    return Manifest("control.path_tracker", "1.0.0")
        .describe("pure pursuit on the path with a speed-scheduled look-ahead; speed from the path, braking ahead of slower stretches")
        .input<msgs::Path>("path", "the path to follow (the newest replaces the last)", true, 2)
        .input<msgs::LocalizationEstimate>("estimate", "where the car is: x, y, yaw, speed of base_link", true, 8)
        .output<msgs::ControlCommand>("command", "steer and pedals, source \"path_tracker\"")
        .param(plugins::vehicle_param().doc("the car's description file: the wheelbase pure pursuit steers with"))
        .param(ParamSpec::number("lookahead_min", d.lookahead_min).in_unit("m").at_least(0.5))
        .param(ParamSpec::number("lookahead_time", d.lookahead_time).in_unit("s").at_least(0).doc("look-ahead = this x speed, clamped"))
        .param(ParamSpec::number("lookahead_max", d.lookahead_max).in_unit("m").at_least(0.5))
        .param(ParamSpec::number("max_steer", d.max_steer).in_unit("rad").at_least(0.01))
        .param(ParamSpec::number("speed_gain", d.speed_gain).at_least(0).doc("pedal per m/s of speed error"))
        .param(ParamSpec::number("preview_time", d.preview_time).in_unit("s").at_least(0).doc("path ahead the speed looks at"))
        .param(ParamSpec::number("decel", d.decel).in_unit("m/s^2").at_least(0.1).doc("braking the speed plan assumes"))
        .param(ParamSpec::boolean("closed", d.closed).doc("the path may be a loop: it is one when its end lies within two of its longest steps of its start (a racing line); false: always open"))
        .on_input("estimate");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    TrackerParams tp;
    tp.wheelbase = plugins::read_vehicle(ctx).wheelbase;
    tp.lookahead_min = p.number("lookahead_min");
    tp.lookahead_time = p.number("lookahead_time");
    tp.lookahead_max = p.number("lookahead_max");
    if (tp.lookahead_min > tp.lookahead_max)
      throw BadInput("parameter 'lookahead_min' (" + std::to_string(tp.lookahead_min) + ") exceeds 'lookahead_max' (" +
                     std::to_string(tp.lookahead_max) + ")");
    tp.max_steer = p.number("max_steer");
    tp.speed_gain = p.number("speed_gain");
    tp.preview_time = p.number("preview_time");
    tp.decel = p.number("decel");
    tp.closed = p.boolean("closed");
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
