// sim.perception_scorer: scores the perception chain against ground truth
// (common/perception_score): the wall detector's d_w, false obstacles, and the range from which
// each pylon is detected in every frame. `require_*` params turn the targets into a
// failed run; the graph tests under tests/graphs/perception_* use them.
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/TrackWorld.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "sim/common/perception_score.hpp"
#include "sim/world_msg.hpp"

#include <cstdio>

namespace {

using namespace brickyard;
using namespace brickyard::sim;

struct Settings {
  PerceptionScoreParams score;
  double require_wall_p95_m = -1, require_wall_valid_fraction = -1;
  std::int64_t require_max_false_obstacles = -1;
  double require_pylon_range_m = -1;
};

ParamBinding<Settings> bindings() {
  using P = PerceptionScoreParams;
  ParamBinding<Settings> b;
  b.bind_choice("wall_side", {{"right", -1}, {"left", 1}}, &Settings::score, &P::wall_side);
  b.bind("match_radius_m", &Settings::score, &P::match_radius).in_unit("m").range(0, 100)
      .doc("an obstacle this close to a pylon is that pylon");
  b.bind("require_wall_p95_m", &Settings::require_wall_p95_m).in_unit("m").range(-100, 100)
      .doc("fail above this p95 of |d_w error|; < 0: off");
  b.bind("require_wall_valid_fraction", &Settings::require_wall_valid_fraction).range(-1, 1)
      .doc("fail if fewer frames carry a valid fit; < 0: off");
  b.bind("require_max_false_obstacles", &Settings::require_max_false_obstacles).range(-1e6, 1e6)
      .doc("fail above this many; < 0: off");
  b.bind("require_pylon_range_m", &Settings::require_pylon_range_m).in_unit("m").range(-1000, 1000)
      .doc("fail if a pylon in view is not reliably detected from this far; < 0: off");
  return b;
}

struct Ports {
  Input<msgs::TrackWorld> world;
  Input<msgs::VehicleState> truth;
  Input<msgs::WallEstimate> wall;
  Input<msgs::ObstacleList> obstacles;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("world", &Ports::world).doc("the world (walls, pylons)").depth(1);
  b.input("truth", &Ports::truth).doc("ground truth").depth(4096);
  b.input("wall", &Ports::wall).doc("a wall detector's output (optional)").optional().depth(256).steps();
  b.input("obstacles", &Ports::obstacles).doc("an obstacle detector's output (optional)").optional().depth(256).steps();
  return b;
}

class PerceptionScorer : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("sim.perception_scorer", "1.0.0")
        .describe("scores wall and obstacle detection against ground truth: d_w error, false obstacles, pylon detection range")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    sp_ = s.score;
    wall_p95_ = s.require_wall_p95_m;
    wall_valid_ = s.require_wall_valid_fraction;
    max_false_ = s.require_max_false_obstacles;
    pylon_range_ = s.require_pylon_range_m;
    io_ = ports().connect(ctx);
  }

  void step(Context&) override { drain(); }

  void deactivate(Context& ctx) override {
    drain();
    if (!score_) {
      ctx.fail("no world was received: nothing scored");
      return;
    }
    const auto& s = *score_;
    const double p50 = PerceptionScore::percentile(s.wall_errors(), 0.5), p95 = PerceptionScore::percentile(s.wall_errors(), 0.95);
    const double valid = s.wall_frames() ? static_cast<double>(s.wall_errors().size()) / s.wall_frames() : 0.0;
    ctx.metric("wall_frames", static_cast<double>(s.wall_frames()));
    ctx.metric("wall_valid_fraction", valid);
    ctx.metric("wall_error_p50_m", p50);
    ctx.metric("wall_error_p95_m", p95);
    ctx.metric("obstacle_frames", static_cast<double>(s.obstacle_frames()));
    ctx.metric("false_obstacles", static_cast<double>(s.false_obstacles()));
    const auto ranges = s.pylon_ranges();
    ctx.metric("pylon_range_m", ranges);
    char b[200];
    if (wall_p95_ >= 0 && !(p95 <= wall_p95_)) {
      std::snprintf(b, sizeof b, "wall distance error p95 %.3f m exceeds the required %.3f m", p95, wall_p95_);
      ctx.fail(b);
    }
    if (wall_valid_ >= 0 && valid < wall_valid_) {
      std::snprintf(b, sizeof b, "a valid wall fit in %.3f of the frames (required %.3f)", valid, wall_valid_);
      ctx.fail(b);
    }
    if (max_false_ >= 0 && static_cast<std::int64_t>(s.false_obstacles()) > max_false_) {
      std::snprintf(b, sizeof b, "%zu false obstacles (at most %lld allowed)", s.false_obstacles(), static_cast<long long>(max_false_));
      ctx.fail(b);
    }
    for (std::size_t k = 0; k < ranges.size() && pylon_range_ >= 0; ++k)
      if (std::isfinite(ranges[k]) && ranges[k] < pylon_range_) {
        std::snprintf(b, sizeof b, "pylon %zu reliably detected only from %.0f m (required %.0f m)", k, ranges[k], pylon_range_);
        ctx.fail(b);
      }
    if ((io_.wall.connected() && s.wall_frames() == 0) ||
        (io_.obstacles.connected() && s.obstacle_frames() == 0))
      ctx.fail("no perception output was scored");
  }

 private:
  void drain() {
    if (!score_) {
      auto w = newest(io_.world);
      if (!w) return;
      track_ = std::make_unique<Track>(from_message(*w));
      score_.emplace(*track_, sp_);
    }
    for (const auto& s : io_.truth.take()) score_->truth(s->header().stamp_ns(), body_pose(*s));
    for (const auto& w : io_.wall.take()) score_->wall(w->header().stamp_ns(), w->distance(), w->valid());
    for (const auto& o : io_.obstacles.take()) {
      std::vector<Eigen::Vector2d> xy;
      for (const auto& ob : o->obstacles()) xy.emplace_back(ob.x(), ob.y());
      score_->obstacles(o->header().stamp_ns(), xy);
    }
  }

  PerceptionScoreParams sp_;
  std::unique_ptr<Track> track_;
  std::optional<PerceptionScore> score_;
  double wall_p95_ = -1, wall_valid_ = -1, pylon_range_ = -1;
  std::int64_t max_false_ = -1;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(PerceptionScorer)
