#pragma once
// The car's recent poses, to place a frame's detections by the pose the car had when the frame was
// taken (a frame arrives after estimates newer than it). Framework-free, header-only.
#include "perception/common/object_tracker.hpp"

#include <cmath>
#include <cstdint>
#include <deque>
#include <optional>

namespace brickyard::perception {

class EgoHistory {
 public:
  struct Pose {
    std::int64_t stamp_ns = 0;
    double x = 0, y = 0, yaw = 0, speed = 0, yaw_rate = 0;
  };
  void add(const Pose& p) {
    if (!poses_.empty() && p.stamp_ns < poses_.back().stamp_ns) return;  // out of order: the newer stands
    poses_.push_back(p);
    while (poses_.size() > kKept) poses_.pop_front();
  }
  // The pose at `stamp_ns`: the latest one not after it carried on by its speed and yaw rate; none
  // when there is none within max_gap_s before it.
  std::optional<EgoPose> at(std::int64_t stamp_ns, double max_gap_s = 0.5) const {
    for (auto it = poses_.rbegin(); it != poses_.rend(); ++it) {
      if (it->stamp_ns > stamp_ns) continue;
      const double dt = (stamp_ns - it->stamp_ns) * 1e-9;
      if (dt > max_gap_s) return std::nullopt;
      const double yaw = it->yaw + it->yaw_rate * dt / 2;  // the heading halfway along the gap
      return EgoPose{it->x + it->speed * dt * std::cos(yaw), it->y + it->speed * dt * std::sin(yaw), it->yaw + it->yaw_rate * dt};
    }
    return std::nullopt;
  }

 private:
  static constexpr std::size_t kKept = 256;  // 2.5 s of a 100 Hz estimator
  std::deque<Pose> poses_;
};

}  // namespace brickyard::perception
