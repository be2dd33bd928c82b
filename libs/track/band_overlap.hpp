#pragma once
// Whether a track's band — its centre line with the widths either side — runs over itself: two
// stretches of track closer than their widths (a loop laid twice, a straight laid over another),
// or a centre line that crosses itself at a shallow angle (two roads merged, not crossing). No
// circuit is like that, and the lateral coordinate of every reader (the simulator's walls, the
// planners' lattice, the referee's contact check) would be ambiguous there.
//
// A crossing at a steep angle is a bridge, one road over the other, as at Suzuka: it is read,
// and said (the TUM Suzuka file crosses itself at 60 degrees; the stack races two laps there).
#include "centre_line.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace brickyard::track {

struct BandOverlap {
  std::size_t a, b;     // the two points (indices into the line) nearest where it happens
  double distance_m;    // between the two stretches' centre lines (0: they cross)
  double widths_m;      // the widths that face each other there, together
  double angle_deg;     // a crossing's angle between the two stretches (0 when they do not cross)
};

// The least angle a crossing must make to be a bridge.
constexpr double kBridgeMinAngleDeg = 30;

struct BandCheck {
  std::vector<BandOverlap> bridges;    // crossings at kBridgeMinAngleDeg or more
  std::optional<BandOverlap> overlap;  // the worst place the band runs over itself, if any
};

// Looks at every pair of stretches more than three facing widths apart along the loop (points
// nearer along the loop than that are one bend), and leaves out the neighbourhood of each
// bridge, where the two roads' bands must overlap. Linear in the points for a real track (a grid
// of cells a little wider than the band).
BandCheck check_band(const CenterLine& line);

}  // namespace brickyard::track
