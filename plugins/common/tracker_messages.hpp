#pragma once
// The path tracker's inputs (libs/control) from the stack's messages: a Path's points and an
// estimate's car state. For the plugins that track a path: control.path_tracker, and the vehicle
// interface's stop along the last path.
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/Path.h>

#include "control/path_tracker.hpp"

#include <vector>

namespace brickyard::plugins {

inline std::vector<control::PathPoint> path_points(const msgs::Path& m) {
  std::vector<control::PathPoint> pts;
  const std::size_t n = m.poses().size();
  pts.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pts.push_back({m.poses()[i].x(), m.poses()[i].y(), i < m.speed().size() ? m.speed()[i] : 0.0});
  return pts;
}

// The car's state at the estimate's stamp (seconds), its lateral speed unknown (0).
inline control::CarState car_state(const msgs::LocalizationEstimate& e) {
  return {e.x(), e.y(), e.yaw(), e.speed(), e.yaw_rate(), 0.0, 1e-9 * static_cast<double>(e.header().stamp_ns())};
}

}  // namespace brickyard::plugins
