#include "line_plan.hpp"

#include "min_curvature.hpp"
#include "min_time.hpp"

namespace brickyard::planning {

track::CenterLine plan_line(const track::CenterLine& centre, const motion::VehicleLimits& limits, double margin) {
  const ClosedLine line{centre.x, centre.y, centre.width_left, centre.width_right};
  MinCurvatureParams p;
  p.margin = margin;
  const MinCurvatureResult r = min_curvature_line(line, p);
  MinTimeParams mp;
  mp.margin = margin;
  const MinTimeResult m = min_time_refine(line, r.offset, limits, mp);
  track::CenterLine out;
  out.x = m.x;
  out.y = m.y;
  out.source = "planned (minimum curvature, refined for minimum time, margin " + std::to_string(margin) + " m) from " + centre.source;
  return out;
}

}  // namespace brickyard::planning
