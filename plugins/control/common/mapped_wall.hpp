#pragma once
// The wall's shape ahead from the map (wall following on road courses), framework-free.
//
// A LiDAR wall fit is a polynomial y(x) over the 20 m it sees well: it cannot bend through a
// hairpin (a wall that turns 90° within view is no function of x) and it does not see the corner
// 200 m ahead that the car must brake for. The map has both. During a GNSS outage the estimate
// is dead reckoning: good to decimetres along the track for seconds, but its heading and lateral
// place drift. So the follower takes the track edge on the wall's side from the map, placed in
// the vehicle frame by the estimate, and lays it onto the LiDAR's wall where the LiDAR sees it
// (register_edge: a turn about the car and a shift across, fitted over the seen stretch). What
// the LiDAR says wins near the car; the map gives the shape beyond. When the two disagree in
// shape (the estimate is off along the track, or the wall is not where the map's edge runs) the
// fit's residual shows it and the follower keeps to the LiDAR's polynomial alone.
#include "track/track.hpp"
#include "wall_line.hpp"

#include <cmath>
#include <vector>

namespace brickyard::control {

// The track's edge on `side` (-1 right, +1 left) at the centre line's points from `behind` metres
// behind the car's place to `ahead` metres ahead, in the vehicle frame of the pose (px, py, yaw)
// (map frame). `hint`: the segment of the last call (updated), -1 for none.
std::vector<EdgePoint> mapped_edge(const track::Track& track, int side, double px, double py, double yaw, double behind,
                                   double ahead, int& hint);

// The turn and shift that lay the mapped edge onto the LiDAR's wall over the stretch.
EdgeRegistration register_edge(const std::vector<EdgePoint>& edge, const WallView& wall, const RegistrationParams& p);

// Points (an edge, a path: anything with x and y) turned about the car by r.turn and moved
// r.shift across: where the registration says they are.
template <class P> std::vector<P> registered(std::vector<P> pts, const EdgeRegistration& r) {
  const double c = std::cos(r.turn), s = std::sin(r.turn);
  for (P& q : pts) {
    const double x = q.x, y = q.y;
    q.x = c * x - s * y;
    q.y = s * x + c * y + r.shift;
  }
  return pts;
}

// Map-frame points in the vehicle frame of the pose (px, py, yaw), map frame.
template <class P> std::vector<P> in_vehicle_frame(std::vector<P> pts, double px, double py, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (P& q : pts) {
    const double dx = q.x - px, dy = q.y - py;
    q.x = c * dx + s * dy;
    q.y = -s * dx + c * dy;
  }
  return pts;
}

// A polyline resampled every `step` metres, each point the mean of those within `half` metres
// along it (fewer at the ends).
std::vector<EdgePoint> smoothed(const std::vector<EdgePoint>& line, double step, double half);

// Signed curvature (left turns positive) at each point of a polyline: the Menger curvature of the
// point with the points about `span` metres before and after it along the line; the ends, where
// no chord fits, take their nearest point's.
std::vector<double> chord_curvature(const std::vector<EdgePoint>& line, double span);

// The line `gap` inward of a wall given as a polyline (smoothed first) (ordered along the car's way) on `side`,
// each point with the speed its curvature allows at p.a_lat (capped at v_cap); the gap is cut
// where the wall bends so tight that the line would be tighter than p.max_curvature.
std::vector<PathPoint> offset_polyline(const std::vector<EdgePoint>& wall, int side, double gap, double v_cap,
                                       const WallLineParams& p);

}  // namespace brickyard::control
