#pragma once
// Whether a prior map is of the track it is used on, checked before a run: the share of the
// track's centre-line points that lie within `reach` of some map point. A mapping drive's map
// covers its whole lap (its LiDARs see tens of metres each side); a map of another place, or in
// another frame, covers little or none of it. Framework-free.
#include "perception/common/points.hpp"

#include <vector>

namespace brickyard::mapping {

using perception::Points;

// Map points are put on a grid of `reach`-sized cells; a centre-line point counts as near when
// its cell or one of the 8 around it holds one (so within reach for sure, and never beyond 2.9
// reach). 0 for an empty centre line.
double share_near_map(const Points& map, const std::vector<double>& x, const std::vector<double>& y, double reach);

}  // namespace brickyard::mapping
