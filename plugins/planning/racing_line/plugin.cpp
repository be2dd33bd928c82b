// planning.racing_line: publishes the optimal racing line as a Path — points, heading, curvature
// and a speed profile from lateral and longitudinal acceleration limits — for the path tracker.
// With the map wired, the line is kept edge_margin inside the track (TUM's IMS line passes
// 0.6 m from the edges, closer than half the car's width).
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/plugin.hpp>

#include "planning/line_params.hpp"
#include "map_msg.hpp"
#include "motion/racing_line.hpp"
#include "newest.hpp"
#include "track/track.hpp"
#include "vehicle_param.hpp"

#include <cmath>
#include <memory>

namespace {

using namespace brickyard;
using brickyard::planning::LineSettings;
using brickyard::planning::LineSource;

struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  LineSettings line;
  double rate_hz = 1;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: the envelope the line is planned and driven with");
  planning::bind_line(b, &Settings::line);
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(0.01, 1000).doc("how often the path is sent again");
  return b;
}

struct Ports {
  Input<msgs::TrackMap> map;
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::ObstacleList> obstacles;
  Output<msgs::Path> path;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("map", &Ports::map)
      .doc("the track: the line is planned for it, or a file's line kept edge_margin inside it (needed with raceline plan)")
      .optional()
      .depth(1);
  // The planner role's: read by planning.road_graph, accepted here so the two planners swap by the plugin's name.
  b.input("estimate", &Ports::estimate).doc("not used: this planner ignores where the car is").optional().depth(1);
  b.input("obstacles", &Ports::obstacles).doc("not used: this planner does not avoid obstacles").optional().depth(1);
  b.output("path", &Ports::path).doc("the line: poses, curvature, speed, s (a closed loop); sent at rate_hz");
  return b;
}

class RacingLineNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("planning.racing_line", "1.0.0")
        .describe("the racing line (planned for the map, or a file's) as a Path with a speed profile")
        .with_ports(ports())
        .plays(roles::planner)
        .parameters(bindings())
        .periodic("rate_hz")
        .check(&check);
  }

  // At validation, the vehicle and racing-line files read and checked as configure will.
  static void check(const CheckView& v) {
    const Settings s = bindings().read(v.params());
    planning::load_line(v, s.line, plugins::read_vehicle_file(v.find_file(s.vehicle)));
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    src_ = planning::load_line(ctx, s.line, plugins::read_vehicle(ctx, s.vehicle));
    io_ = ports().connect(ctx);
    if (src_.plan && !io_.map.connected()) throw BadInput("raceline plan: input 'map' must be wired (the line is planned for its track)");
  }

  void step(Context& ctx) override {
    io_.estimate.take();  // drained, unused
    io_.obstacles.take();
    if (!path_) {
      track::CenterLine line = src_.file_line;
      if (io_.map.connected()) {
        auto w = plugins::newest(io_.map);
        if (!w) return;
        try {
          line = planning::line_points(src_, std::make_unique<track::Track>(plugins::from_message(*w)).get());
        } catch (const planning::LineLeavesTrack& e) {
          throw BadInput(src_.file_line.source + ": " + e.what());
        } catch (const std::exception& e) {  // a malformed map: the file's line as it is; nothing to plan on
          if (src_.plan) throw BadInput(std::string("raceline plan: the map's track cannot be planned on: ") + e.what());
          ctx.log(LogLevel::warn, std::string("map unusable (") + e.what() + "): the racing line is not kept inside the edges");
        }
      }
      const motion::RacingLine r = motion::make_racing_line(line, src_.limits, src_.curvature_smooth_m);
      auto m = std::make_shared<msgs::Path>();
      m->header().frame_id("map");
      const std::size_t n = r.x.size();
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (i + 1) % n;
        msgs::Pose2D pose;
        pose.x(r.x[i]);
        pose.y(r.y[i]);
        pose.yaw(std::atan2(r.y[j] - r.y[i], r.x[j] - r.x[i]));
        m->poses().push_back(pose);
      }
      m->curvature(r.kappa);
      m->speed(r.speed);
      m->s(r.s);
      path_ = m;
      ctx.metric("points", static_cast<double>(n));
      ctx.metric("length_m", r.length);
      ctx.metric("planned_lap_s", planning::planned_lap(r));
    }
    auto m = std::make_shared<msgs::Path>(*path_);
    m->header().stamp_ns(ctx.now_ns());
    m->header().seq(seq_++);
    io_.path.publish(std::shared_ptr<const msgs::Path>(m));
  }

 private:
  LineSource src_;
  std::shared_ptr<const msgs::Path> path_;
  std::uint32_t seq_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(RacingLineNode)
