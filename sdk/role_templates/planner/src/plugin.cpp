// example.my_plugin: a planner (docs/roles.md: in estimate, out path; may take map and
// obstacles), the thin adapter between Brickyard and the algorithm in centre_line_path.hpp. It
// fits any graph node whose role is "planner": `brickyard run race.json --set
// planner.plugin=example.my_plugin --plugin-path build`.
#include "centre_line_path.hpp"

#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/plugin.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace {

using namespace brickyard;

ParamBinding<my_plugin::PathSettings> bindings() {
  ParamBinding<my_plugin::PathSettings> b;
  b.bind("ahead_m", &my_plugin::PathSettings::ahead_m).range(10.0, 5000.0).in_unit("m").doc("how far ahead of the car the path reaches");
  b.bind("a_lat", &my_plugin::PathSettings::a_lat).range(0.5, 30.0).in_unit("m/s^2").doc("the lateral acceleration allowed in a turn");
  b.bind("a_brake", &my_plugin::PathSettings::a_brake).range(0.5, 30.0).in_unit("m/s^2").doc("the deceleration planned before a turn");
  b.bind("v_max", &my_plugin::PathSettings::v_max).range(1.0, 120.0).in_unit("m/s").doc("the top speed");
  return b;
}

// The planner role's ports: the names and types are the role's (brickyard/roles.hpp), so the
// plugin drops into any graph made for a planner.
struct Ports {
  Input<msgs::LocalizationEstimate> estimate;
  Input<msgs::TrackMap> map;
  Input<msgs::ObstacleList> obstacles;
  Output<msgs::Path> path;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("estimate", &Ports::estimate).doc("the car's pose: a path each time it comes").steps();
  b.input("map", &Ports::map).doc("the track: the path follows its centre line");
  b.input("obstacles", &Ports::obstacles).optional().doc("taken and ignored: this starting point does not avoid");
  b.output("path", &Ports::path).doc("the centre line ahead of the car, in the map frame");
  return b;
}

class MyPlugin : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("example.my_plugin", "0.1.0")
        .describe("A planner: the track's centre line ahead of the car at the speed its curvature allows")
        .with_ports(ports())
        .parameters(bindings())
        .plays(roles::planner);
  }

  void configure(Context& ctx) override {
    settings_ = bindings().read(ctx.params());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (const auto& m : io_.map.take()) take_map(ctx, *m);
    io_.obstacles.take();
    for (const auto& e : io_.estimate.take())
      if (line_) publish_path(*e);
  }

  void deactivate(Context& ctx) override { ctx.metric("paths", static_cast<double>(seq_)); }

 private:
  void take_map(Context& ctx, const msgs::TrackMap& map) {
    try {
      line_.emplace(map.x(), map.y());
    } catch (const std::invalid_argument& e) {
      ctx.log(LogLevel::warn, std::string("map ignored: ") + e.what());
    }
  }

  void publish_path(const msgs::LocalizationEstimate& car) {
    msgs::Path m;
    m.header().stamp_ns(car.header().stamp_ns());
    m.header().seq(seq_++);
    m.header().frame_id("map");
    for (const auto& p : line_->ahead_of(car.x(), car.y(), settings_)) {
      msgs::Pose2D pose;
      pose.x(p.x);
      pose.y(p.y);
      pose.yaw(p.yaw);
      m.poses().push_back(pose);
      m.curvature().push_back(p.curvature);
      m.speed().push_back(p.speed);
      m.s().push_back(p.s);
    }
    io_.path.publish(std::move(m));
  }

  my_plugin::PathSettings settings_;
  std::optional<my_plugin::CentreLinePath> line_;
  Ports io_;
  std::uint32_t seq_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(MyPlugin)
