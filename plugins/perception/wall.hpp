#pragma once
// WallFit <-> WallEstimate, shared by the wall and obstacle detectors.
#include <brickyard/msgs/WallEstimate.h>

#include "perception/common/wall_fit.hpp"

#include <cmath>

namespace brickyard::perception {

inline msgs::WallEstimate wall_message(const WallFit& w, double lookahead, std::int64_t stamp_ns, std::uint32_t seq) {
  msgs::WallEstimate m;
  m.header().stamp_ns(stamp_ns);
  m.header().seq(seq);
  m.header().frame_id("vehicle");
  m.coefficients(w.coefficients);
  m.distance(w.distance);
  m.heading(w.heading);
  m.curvature(w.curvature);
  m.lookahead(lookahead);
  m.residual(w.residual);
  m.lean(w.lean);
  m.x_min(w.x_min);
  m.x_max(w.x_max);
  m.point_count(static_cast<std::uint32_t>(w.points));
  for (int c : w.members) m.clusters().push_back(static_cast<std::uint32_t>(c));
  m.valid(w.valid);
  return m;
}

inline WallFit wall_fit(const msgs::WallEstimate& m) {
  WallFit w;
  w.coefficients = m.coefficients();
  w.distance = m.distance();
  w.heading = m.heading();
  w.curvature = m.curvature();
  w.residual = m.residual();
  w.lean = m.lean();
  w.x_min = m.x_min();
  w.x_max = m.x_max();
  w.points = m.point_count();
  for (auto c : m.clusters()) w.members.push_back(static_cast<int>(c));
  bool finite = std::isfinite(w.distance) && std::isfinite(w.lean) && std::isfinite(w.x_min) && std::isfinite(w.x_max);
  for (double c : w.coefficients) finite = finite && std::isfinite(c);
  w.valid = m.valid() && !w.coefficients.empty() && finite && w.x_min <= w.x_max;  // a malformed estimate is no wall
  return w;
}

}  // namespace brickyard::perception
