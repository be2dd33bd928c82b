#pragma once
// The car's recent pose estimates, bounded, and the pose at a stamp: what every consumer of a
// LiDAR frame (the planner's obstacles, the scan mapper's guess, the wall follower's edges) needs,
// because a frame is the surroundings at its own stamp and the estimate runs at its own rate
// (125 Hz, not the LiDAR's 20 Hz): the nearest estimate may be 4 ms off, 0.3 m at 80 m/s.
// Framework-free, header-only; `Estimate` is whatever the caller keeps beside each pose (the
// message, or its spreads).
#include "math/planar_pose.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>

namespace brickyard::math {

template <class Estimate>
class EstimateHistory {
 public:
  struct Sample {
    std::int64_t stamp_ns = 0;
    PlanarPose pose;
    Estimate estimate;
  };

  // The pose at a stamp and the sample to take the rest from (spreads, status): the nearer of the
  // two around the stamp (the newer at a tie), else the nearest.
  struct PoseAt {
    PlanarPose pose;
    const Sample* nearer = nullptr;
    bool interpolated = false;
  };

  // Keeps the newest `capacity` samples (at least one).
  explicit EstimateHistory(std::size_t capacity) : capacity_(capacity > 0 ? capacity : 1) {}

  // In arrival order: a sample that arrives late still counts by its stamp.
  void add(std::int64_t stamp_ns, const PlanarPose& pose, Estimate estimate) {
    samples_.push_back({stamp_ns, pose, std::move(estimate)});
    if (samples_.size() > capacity_) samples_.pop_front();
  }

  bool empty() const { return samples_.empty(); }
  std::size_t size() const { return samples_.size(); }
  const Sample& newest() const { return samples_.back(); }  // the last to arrive; not empty()

  // The sample whose stamp is nearest: the newest unless another is strictly nearer (then the
  // first of those to arrive). The distance is exact and cannot overflow (unsigned), however odd
  // the stamps: Unix-epoch nanoseconds are past double's 2^53. Null when empty.
  const Sample* nearest(std::int64_t stamp_ns) const {
    if (samples_.empty()) return nullptr;
    auto apart = [stamp_ns](const Sample& s) {
      const auto a = static_cast<std::uint64_t>(s.stamp_ns), b = static_cast<std::uint64_t>(stamp_ns);
      return s.stamp_ns >= stamp_ns ? a - b : b - a;
    };
    const Sample* best = &samples_.back();
    for (const Sample& s : samples_)
      if (apart(s) < apart(*best)) best = &s;
    return best;
  }

  // The pose at a stamp: interpolated between the latest sample at or before it and the earliest
  // at or after it (the heading the short way round), else the nearest's. None when empty.
  std::optional<PoseAt> at(std::int64_t stamp_ns) const {
    const Sample* n = nearest(stamp_ns);
    if (!n) return std::nullopt;
    const Sample *before = nullptr, *after = nullptr;
    for (const Sample& s : samples_) {
      if (s.stamp_ns <= stamp_ns && (!before || s.stamp_ns > before->stamp_ns)) before = &s;
      if (s.stamp_ns >= stamp_ns && (!after || s.stamp_ns < after->stamp_ns)) after = &s;
    }
    if (!before || !after || after->stamp_ns <= before->stamp_ns) return PoseAt{n->pose, n, false};
    const PlanarPose p = interpolate_pose(before->stamp_ns, before->pose, after->stamp_ns, after->pose, stamp_ns);
    const std::uint64_t to_before = static_cast<std::uint64_t>(stamp_ns) - static_cast<std::uint64_t>(before->stamp_ns);
    const std::uint64_t span = static_cast<std::uint64_t>(after->stamp_ns) - static_cast<std::uint64_t>(before->stamp_ns);
    const bool a_nearer = to_before < span - to_before;
    return PoseAt{p, a_nearer ? before : after, true};
  }

 private:
  std::size_t capacity_;
  std::deque<Sample> samples_;
};

}  // namespace brickyard::math
