// perception.clustering: Euclidean clustering of the vertical features (common/clustering.hpp).
#include <brickyard/msgs/ClusterList.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "perception/messages.hpp"
#include "perception/common/clustering.hpp"

namespace {

using namespace brickyard;
using namespace brickyard::perception;

ParamBinding<ClusterParams> bindings() {
  ParamBinding<ClusterParams> b;
  b.bind("tolerance", &ClusterParams::tolerance).in_unit("m").range(0.01, 100).doc("points closer than this are connected");
  b.bind("min_size", &ClusterParams::min_size).range(1, 1e7).doc("smaller clusters are dropped");
  b.bind("max_size", &ClusterParams::max_size).range(1, 1e7).doc("larger clusters are dropped, not split (as PCL)");
  b.not_above("min_size", "max_size");
  return b;
}

struct Ports {
  Input<msgs::PointCloud> points;
  Output<msgs::ClusterList> clusters;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("points", &Ports::points).doc("points to cluster (any frame the message's sensor pose maps to the vehicle's)").depth(4).steps();
  b.output("clusters", &Ports::clusters).doc("clusters in the vehicle frame, in order of their first point");
  return b;
}

class ClusteringNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.clustering", "1.0.0")
        .describe("Euclidean clustering (hash grid + union-find; the same partition as PCL's EuclideanClusterExtraction)")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    clustering_ = EuclideanClustering(bindings().read(ctx.params()));
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    for (auto& m : io_.points.take()) {
      pts_.clear();
      try {
        append_vehicle_points(*m, pts_);
      } catch (const std::runtime_error& e) {
        if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": cloud skipped");
        continue;
      }
      clustering_.run(pts_, clusters_);
      io_.clusters.publish(cluster_list(pts_, clusters_, m->header().stamp_ns(), seq_++));
      ++frames_;
      total_ += clusters_.size();
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("malformed_clouds", static_cast<double>(malformed_));
    ctx.metric("clusters_per_frame", frames_ ? static_cast<double>(total_) / frames_ : 0.0);
  }

 private:
  EuclideanClustering clustering_;
  Points pts_;
  std::vector<std::vector<int>> clusters_;
  Ports io_;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, malformed_ = 0, total_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ClusteringNode)
