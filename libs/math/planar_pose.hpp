#pragma once
// A planar pose (x, y, yaw) at a stamp between two stamped ones, shared by the consumers that
// place a LiDAR frame by its stamp (the planner's obstacles, the scan mapper's guess): the pose
// estimate runs at its own rate (125 Hz), not the LiDAR's 20 Hz, so the nearest estimate may be
// 4 ms from the frame's stamp, 0.3 m at 80 m/s. Framework-free, header-only.
#include <cmath>
#include <cstdint>

namespace brickyard::math {

struct PlanarPose {
  double x = 0, y = 0, yaw = 0;
};

// Linear between a (at ta) and b (at tb), the heading the short way round; a when tb <= ta.
inline PlanarPose interpolate_pose(std::int64_t ta, const PlanarPose& a, std::int64_t tb, const PlanarPose& b, std::int64_t t) {
  if (tb <= ta) return a;
  const double u = static_cast<double>(t - ta) / static_cast<double>(tb - ta);
  return {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.yaw + u * std::remainder(b.yaw - a.yaw, 2 * M_PI)};
}

}  // namespace brickyard::math
