#pragma once
// What the mapping nodes (scan_mapper, map_localizer) share of their messages: a frame put
// together from the ground filter's two clouds of one stamp, and the pose found as a
// LocalizationEstimate. Plugin-side (SDK).
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>

#include "mapping/common/mapping_run.hpp"
#include "perception/messages.hpp"

#include <cstdint>
#include <deque>
#include <memory>

namespace brickyard::mapping {

// The ground filter's vertical features, kept a few frames to meet their ground (the same stamp).
class FrameFeatures {
 public:
  void add(std::shared_ptr<const msgs::PointCloud> features) {
    kept_.push_back(std::move(features));
    if (kept_.size() > 8) kept_.pop_front();
  }
  // `ground`'s points (how many: `n_ground`), then its stamp's features, into `pts` (vehicle
  // frame). Throws std::runtime_error on a malformed cloud.
  void assemble(const msgs::PointCloud& ground, Points& pts, std::size_t* n_ground = nullptr) const {
    perception::append_vehicle_points(ground, pts);
    if (n_ground) *n_ground = pts.size();
    for (const auto& f : kept_)
      if (f->header().stamp_ns() == ground.header().stamp_ns()) perception::append_vehicle_points(*f, pts);
  }

 private:
  std::deque<std::shared_ptr<const msgs::PointCloud>> kept_;
};

inline msgs::LocalizationEstimate pose_message(const FramePose& f, std::uint32_t seq) {
  msgs::LocalizationEstimate m;
  m.header().stamp_ns(f.stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("map");
  m.x(f.x);
  m.y(f.y);
  m.yaw(f.yaw);
  m.speed(f.speed);
  m.yaw_rate(f.yaw_rate);
  m.covariance(f.covariance);
  m.update_case(f.update_case);
  m.status(f.status);
  return m;
}

}  // namespace brickyard::mapping
