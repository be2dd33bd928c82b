// perception.wall_detector: the longest cluster on one side is the wall; a least-squares
// polynomial y(x) at z = 0 (common/wall_fit.hpp).
#include <brickyard/msgs/ClusterList.h>
#include <brickyard/msgs/WallEstimate.h>
#include <brickyard/plugin.hpp>

#include "../messages.hpp"
#include "../wall.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::perception;

class WallDetectorNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.wall_detector", "1.0.0")
        .describe("the longest cluster on the configured side is the wall: least-squares polynomial y(x) at z = 0 (Eigen), "
                  "d_w = y(0), heading and curvature at a look-ahead")
        .input<msgs::ClusterList>("clusters", "clusters, vehicle frame", true, 4)
        .output<msgs::WallEstimate>("wall", "the fitted wall, every frame (valid: false when there is none)")
        .param(ParamSpec::string("side", "right").one_of({"right", "left"}))
        .param(ParamSpec::integer("degree", 2).range(1, 5).doc("of the polynomial y(x)"))
        .param(ParamSpec::boolean("lean", true).doc("also fit y = p(x) + k z: the wall's lean in a rolled car (banking)"))
        .param(ParamSpec::number("lookahead", 10).in_unit("m").at_least(0).doc("where heading and curvature are taken"))
        .param(ParamSpec::integer("min_points", 30).at_least(1).doc("fewer points: not valid"))
        .param(ParamSpec::number("min_length", 5).in_unit("m").at_least(0).doc("shorter x extent: not valid"))
        .param(ParamSpec::number("max_residual", 0.3).in_unit("m").at_least(0).doc("larger RMS residual: not valid"))
        .on_input("clusters");
  }

  void configure(Context& ctx) override {
    const Params& p = ctx.params();
    wp_.side = p.string("side") == "left" ? 1 : -1;
    wp_.degree = static_cast<int>(p.integer("degree"));
    wp_.lean = p.boolean("lean");
    wp_.lookahead = p.number("lookahead");
    wp_.min_points = static_cast<int>(p.integer("min_points"));
    wp_.min_length = p.number("min_length");
    wp_.max_residual = p.number("max_residual");
    in_ = ctx.input<msgs::ClusterList>("clusters");
    out_ = ctx.output<msgs::WallEstimate>("wall");
  }

  void step(Context& ctx) override {
    for (auto& m : in_.take()) {
      try {
        read_clusters(*m, pts_, clusters_);
      } catch (const std::runtime_error& e) {
        if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
        continue;
      }
      const WallFit w = fit_wall(pts_, clusters_, wp_);
      out_.publish(wall_message(w, wp_.lookahead, m->header().stamp_ns(), seq_++));
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
  Input<msgs::ClusterList> in_;
  Output<msgs::WallEstimate> out_;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, valid_ = 0, malformed_ = 0;
  double residual_sum_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(WallDetectorNode)
