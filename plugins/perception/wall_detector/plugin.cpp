// perception.wall_detector: the longest cluster on one side is the wall; a least-squares
// polynomial y(x) at z = 0 (common/wall_fit.hpp).
#include <brickyard/msgs/ClusterList.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "perception/messages.hpp"
#include "perception/wall.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::perception;

ParamBinding<WallParams> bindings() {
  using W = WallParams;
  ParamBinding<W> b;
  b.bind_choice("side", {{"right", -1}, {"left", 1}}, &W::side);
  b.bind("degree", &W::degree).range(1, 5).doc("of the polynomial y(x)");
  b.bind("lean", &W::lean).doc("also fit y = p(x) + k z: the wall's lean in a rolled car (banking)");
  b.bind("lookahead", &W::lookahead).in_unit("m").range(0, 1000).doc("where heading and curvature are taken");
  b.bind("min_points", &W::min_points).range(1, 1e7).doc("fewer points: not valid");
  b.bind("min_length", &W::min_length).in_unit("m").range(0, 1000).doc("shorter x extent: not valid");
  b.bind("max_residual", &W::max_residual).in_unit("m").range(0, 100).doc("larger RMS residual: not valid");
  b.bind("join_gap", &W::join_gap).in_unit("m").range(0, 1000)
      .doc("a cluster starting this far past the wall's end may continue it (far stripes of a grazed wall)");
  b.bind("join_margin", &W::join_margin).in_unit("m").range(0, 100).doc("from the wall's extrapolated local fit...");
  b.bind("join_slope", &W::join_slope).range(0, 100).doc("...plus this per metre past the end");
  b.bind("fit_range", &W::fit_range).in_unit("m").range(1, 1000).doc("the polynomial fits the wall's points with x <= this...");
  b.bind("fit_behind", &W::fit_behind).in_unit("m").range(0, 1000)
      .doc("...and x >= -fit_behind (a wall bending round a turn is fitted where the car goes)");
  return b;
}

struct Ports {
  Input<msgs::ClusterList> clusters;
  Output<msgs::WallEstimate> wall;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("clusters", &Ports::clusters).doc("clusters, vehicle frame").depth(4).steps();
  b.output("wall", &Ports::wall).doc("the fitted wall, every frame (valid: false when there is none)");
  return b;
}

class WallDetectorNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.wall_detector", "1.0.0")
        .describe("the longest cluster on the configured side is the wall, grown through the clusters that continue it; "
                  "least-squares polynomial y(x) at z = 0 (Eigen), d_w = y(0), heading and curvature at a look-ahead")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    wp_ = bindings().read(ctx.params());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (auto& m : io_.clusters.take()) {
      try {
        read_clusters(*m, pts_, clusters_);
      } catch (const std::runtime_error& e) {
        if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
        continue;
      }
      const WallFit w = fit_wall(pts_, clusters_, wp_);
      io_.wall.publish(wall_message(w, wp_.lookahead, m->header().stamp_ns(), seq_++));
      ++frames_;
      if (w.valid) {
        ++valid_;
        residual_sum_ += w.residual;
      }
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("valid_frames", static_cast<double>(valid_));
    ctx.metric("malformed_frames", static_cast<double>(malformed_));
    ctx.metric("mean_residual_m", valid_ ? residual_sum_ / valid_ : 0.0);
  }

 private:
  WallParams wp_;
  Points pts_;
  std::vector<std::vector<int>> clusters_;
  Ports io_;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, valid_ = 0, malformed_ = 0;
  double residual_sum_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(WallDetectorNode)
