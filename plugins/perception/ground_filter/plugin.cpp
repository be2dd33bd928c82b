// perception.ground_filter: merges the car's LiDARs into the vehicle frame and splits the voxels
// into ground and vertical features (the paper's hashed z-vote, common/ground_filter.hpp).
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "perception/messages.hpp"
#include "perception/common/ground_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>

namespace {

using namespace brickyard;
using namespace brickyard::perception;

using CloudPtr = std::shared_ptr<const msgs::PointCloud>;

struct Settings {
  GroundParams filter;  // the defaults live with the algorithm
  double sync_window_s = 0.025;
};

ParamBinding<Settings> bindings() {
  using G = GroundParams;
  ParamBinding<Settings> b;
  b.bind("leaf", &Settings::filter, &G::leaf).in_unit("m").range(0.01, 10).doc("voxel size");
  b.bind("cell", &Settings::filter, &G::cell).in_unit("m").range(0.01, 10).doc("2-D vote grid");
  b.bind("min_votes", &Settings::filter, &G::min_votes).range(1, 1000).doc("voxels in a cell for a vertical feature");
  b.bind("min_height", &Settings::filter, &G::min_height).in_unit("m").range(0, 100).doc("z extent of a vertical feature's voxels");
  b.bind("ground_band", &Settings::filter, &G::ground_band).in_unit("m").range(0, 100)
      .doc("in a vertical cell, voxels this close to the road it stands on are road");
  b.bind("sync_window_s", &Settings::sync_window_s).in_unit("s").range(0, 1)
      .doc("clouds stamped within this of the frame's first belong to one frame");
  return b;
}

struct Ports {
  std::array<Input<msgs::PointCloud>, 3> lidar;
  Input<msgs::LocalizationEstimate> estimate;
  Output<msgs::PointCloud> points, ground;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.inputs("lidar", &Ports::lidar)
      .doc("a LiDAR's cloud (sensor frame, its pose in the message); lidar1 and lidar2 optional")
      .required_first(1)
      .depth(4)
      .steps();
  b.input("estimate", &Ports::estimate)
      .doc("the car's speed and yaw rate: each point moved to the frame's stamp by the motion since it was measured "
           "(its cloud's stamp and time_offset; unwired: points taken as measured at the frame's stamp)")
      .optional()
      .depth(8);
  b.output("points", &Ports::points).doc("vertical features: the non-ground voxel centroids, vehicle frame");
  b.output("ground", &Ports::ground).doc("the ground voxel centroids, vehicle frame");
  return b;
}

class GroundFilterNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.ground_filter", "1.0.0")
        .describe("merges up to 3 LiDARs into the vehicle frame, voxel filter, then the paper's hashed z-vote: "
                  "cells of few voxels or little height are ground (no slope limit: holds on banked turns)")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    const GroundParams& g = s.filter;
    filter_ = GroundFilter(g);
    io_ = ports().connect(ctx);
    int sensors = 0;
    for (int i = 0; i < 3; ++i)
      if (io_.lidar[i].connected()) slot_[i] = sensors++;
    sets_.emplace(sensors, static_cast<std::int64_t>(s.sync_window_s * 1e9));
  }

  void step(Context& ctx) override {
    // Offered in stamp order across the inputs, so a backlog on one does not split frames.
    std::vector<std::tuple<std::int64_t, int, CloudPtr>> arrived;
    for (int i = 0; i < 3; ++i) {
      if (slot_[i] < 0) continue;
      for (auto& c : io_.lidar[i].take()) arrived.emplace_back(c->header().stamp_ns(), slot_[i], c);
    }
    std::stable_sort(arrived.begin(), arrived.end(),
                     [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b) || (std::get<0>(a) == std::get<0>(b) && std::get<1>(a) < std::get<1>(b)); });
    for (auto& [stamp, slot, c] : arrived)
      for (auto& set : sets_->offer(slot, stamp, c)) process(ctx, set);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("partial_frames", static_cast<double>(sets_->partial()));
    ctx.metric("late_clouds", static_cast<double>(sets_->late()));
    ctx.metric("malformed_clouds", static_cast<double>(malformed_));
    ctx.metric("points_per_frame", frames_ ? static_cast<double>(points_in_) / frames_ : 0.0);
    ctx.metric("voxels_per_frame", frames_ ? static_cast<double>(voxels_) / frames_ : 0.0);
    ctx.metric("feature_voxels_per_frame", frames_ ? static_cast<double>(features_) / frames_ : 0.0);
  }

 private:
  void process(Context& ctx, const std::vector<CloudPtr>& set) {
    merged_.clear();
    const std::int64_t stamp = set.front()->header().stamp_ns();
    const std::optional<PlanarMotion> motion = motion_of(io_.estimate.latest());
    for (const auto& c : set) {
      try {
        append_vehicle_points(*c, merged_, motion ? &*motion : nullptr, stamp);
      } catch (const std::runtime_error& e) {
        if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": cloud skipped");
      }
    }
    filter_.run(merged_, result_);
    io_.points.publish(vehicle_cloud(result_.voxels, &result_.ground, 0, stamp, seq_));
    io_.ground.publish(vehicle_cloud(result_.voxels, &result_.ground, 1, stamp, seq_));
    ++seq_;
    ++frames_;
    points_in_ += merged_.size();
    voxels_ += result_.voxels.size();
    for (auto g : result_.ground) features_ += g == 0;
  }

  // The estimate's speed and yaw rate; none unwired, before the first, or not finite (a broken
  // estimate must not move every point off the map).
  static std::optional<PlanarMotion> motion_of(const std::shared_ptr<const msgs::LocalizationEstimate>& e) {
    if (!e || !std::isfinite(e->speed()) || !std::isfinite(e->yaw_rate())) return std::nullopt;
    return PlanarMotion{e->speed(), e->yaw_rate()};
  }

  GroundFilter filter_;
  GroundResult result_;
  Points merged_;
  Ports io_;
  std::array<int, 3> slot_{-1, -1, -1};
  std::optional<FrameSet<CloudPtr>> sets_;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, malformed_ = 0, points_in_ = 0, voxels_ = 0, features_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(GroundFilterNode)
