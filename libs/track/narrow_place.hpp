#pragma once
// Where a track is too narrow for a car: a map the car cannot drive is bad input, refused before
// anything runs (map.track_file, at validation and in configure).
#include "track/centre_line.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace brickyard::track {

// The first place where the track is narrower than the car, as "s = X m: W m wide"; empty when
// the car fits everywhere.
inline std::string narrower_than(const CenterLine& c, double car_width) {
  double s = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (i > 0) s += std::hypot(c.x[i] - c.x[i - 1], c.y[i] - c.y[i - 1]);
    const double w = c.width_left[i] + c.width_right[i];
    if (w < car_width) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "at s = %.1f m (point %zu) it is %.2f m wide", s, i + 1, w);
      return buf;
    }
  }
  return {};
}

}  // namespace brickyard::track
