// perception.obstacle_detector: clusters inside the drivable corridor that are not wall
// (common/obstacles.hpp). Each frame of clusters is matched with the wall estimates of the same
// stamp, so the result does not depend on which detector the executive steps first.
#include <brickyard/msgs/ClusterList.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "perception/messages.hpp"
#include "perception/wall.hpp"
#include "perception/common/obstacles.hpp"
#include "perception/common/stamp_match.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::perception;

// Frames of clusters with the wall fits of their stamp: the messages kept until then.
using Match = StampMatch<std::shared_ptr<const msgs::ClusterList>, std::shared_ptr<const msgs::WallEstimate>>;

ParamBinding<ObstacleParams> bindings() {
  using O = ObstacleParams;
  ParamBinding<O> b;
  b.bind("max_lateral", &O::max_lateral).in_unit("m").range(0, 1000).doc("corridor half width when no wall is fitted");
  b.bind("corridor_width", &O::corridor_width).in_unit("m").range(0, 1000)
      .doc("corridor: this far inward of the fitted wall, following it round turns");
  b.bind("max_range", &O::max_range).in_unit("m").range(0, 1000).doc("how far ahead");
  b.bind("max_behind", &O::max_behind).in_unit("m").range(0, 1000).doc("how far behind");
  b.bind("wall_margin", &O::wall_margin).in_unit("m").range(0, 100)
      .doc("a cluster this close to a fitted wall is wall");
  b.bind("wall_reach", &O::wall_reach).in_unit("m").range(0, 1000)
      .doc("how far past the ends of a fitted wall's points it marks all that lies beyond it as wall");
  b.bind("wall_depth", &O::wall_depth).in_unit("m").range(0, 100)
      .doc("further on (the wall's line extrapolated), only this deep beyond the line is wall");
  b.bind("max_length", &O::max_length).in_unit("m").range(0, 1000).doc("longer clusters are structure, not obstacles");
  b.bind("min_height", &O::min_height).in_unit("m").range(0, 100).doc("less z extent: a scan row's streak, not an obstacle");
  b.bind("flat_thickness", &O::flat_thickness).in_unit("m").range(0, 100)
      .doc("a cluster thinner than this across its best plane, lying within flat_tilt_deg of level, is ground");
  b.bind("flat_tilt_deg", &O::flat_tilt_deg).in_unit("deg").range(0, 90);
  b.bind("stack_gap", &O::stack_gap).in_unit("m").range(0, 100)
      .doc("clusters whose footprints come this close are one object (a far pylon's row streaks)");
  b.bind("min_points", &O::min_points).range(1, 1e7);
  return b;
}

struct Ports {
  Input<msgs::ClusterList> clusters;
  Input<msgs::WallEstimate> wall_right, wall_left;
  Output<msgs::ObstacleList> obstacles;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("clusters", &Ports::clusters).doc("clusters, vehicle frame").depth(8).steps();
  b.input("wall_right", &Ports::wall_right).doc("the right wall fit of the same frames (optional)").optional().depth(8).steps();
  b.input("wall_left", &Ports::wall_left).doc("the left wall fit of the same frames (optional)").optional().depth(8).steps();
  b.output("obstacles", &Ports::obstacles).doc("obstacles, vehicle frame, every frame");
  return b;
}

class ObstacleDetectorNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.obstacle_detector", "1.0.0")
        .describe("clusters inside the drivable corridor (|y| limit, cut by the fitted walls) that are not wall -> obstacles")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    op_ = bindings().read(ctx.params());
    io_ = ports().connect(ctx);
    match_ = Match({io_.wall_right.connected(), io_.wall_left.connected()});
  }

  void step(Context& ctx) override {
    for (auto& m : io_.clusters.take()) match_.add_frame(m->header().stamp_ns(), m);
    for (int s = 0; s < 2; ++s)
      for (auto& w : wall_in(s).take()) match_.add_wall(s, w->header().stamp_ns(), w);
    while (auto m = match_.next()) {
      std::vector<std::pair<WallFit, int>> walls;
      for (const auto& [w, side] : m->walls) walls.emplace_back(wall_fit(*w), side);
      process(ctx, *m->frame, walls);
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("frames_without_wall_fit", static_cast<double>(match_.unmatched()));
    ctx.metric("malformed_frames", static_cast<double>(malformed_));
    ctx.metric("obstacles_per_frame", frames_ ? static_cast<double>(total_) / frames_ : 0.0);
  }

 private:
  void process(Context& ctx, const msgs::ClusterList& m, const std::vector<std::pair<WallFit, int>>& walls) {
    try {
      read_clusters(m, pts_, clusters_);
    } catch (const std::runtime_error& e) {
      if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
      return;
    }
    msgs::ObstacleList out;
    out.header().stamp_ns(m.header().stamp_ns());
    out.header().seq(seq_++);
    out.header().frame_id("vehicle");
    for (const Obstacle& o : find_obstacles(pts_, clusters_, walls, op_)) {
      msgs::Obstacle x;
      x.x(o.centroid.x()); x.y(o.centroid.y()); x.z(o.centroid.z());
      x.size_x(o.size.x()); x.size_y(o.size.y()); x.size_z(o.size.z());
      for (const auto& q : o.outline) x.outline_x().push_back(q.x()), x.outline_y().push_back(q.y());
      x.box_yaw(o.box_yaw);
      x.point_count(static_cast<std::uint32_t>(o.points));
      out.obstacles().push_back(x);
    }
    total_ += out.obstacles().size();
    ++frames_;
    io_.obstacles.publish(std::move(out));
  }

  // Side s of walls_: 0 right, 1 left.
  Input<msgs::WallEstimate>& wall_in(int s) { return s == 0 ? io_.wall_right : io_.wall_left; }

  ObstacleParams op_;
  Points pts_;
  std::vector<std::vector<int>> clusters_;
  Match match_;
  Ports io_;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, malformed_ = 0, total_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ObstacleDetectorNode)
