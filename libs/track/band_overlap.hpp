#pragma once
// Whether a track's band — its centre line with the widths either side — runs over itself: a
// centre line that crosses itself (a figure 8), or two stretches of track closer than their
// widths (a loop driven twice, a straight laid over another). No circuit is like that, and the
// lateral coordinate of every reader (the simulator's walls, the planners' lattice, the
// referee's contact check) would be ambiguous there (issue 20).
#include "centre_line.hpp"

#include <cstddef>
#include <optional>

namespace brickyard::track {

struct BandOverlap {
  std::size_t a, b;     // the two points (indices into the line) nearest where it happens
  double distance_m;    // between the two stretches' centre lines (0: they cross)
  double widths_m;      // the widths that face each other there, together
};

// Looks at every pair of stretches more than three facing widths apart along the loop; points
// nearer along the loop than that are one bend. Linear in the points for a real track (a grid of
// cells a little wider than the band).
std::optional<BandOverlap> find_band_overlap(const CenterLine& line);

}  // namespace brickyard::track
