#pragma once
// Where a road is banked and how much: a bank angle per centre-line point from a few numbers
// (none, constant, in turns by curvature, or listed ranges of s). Framework-free.
#include "centre_line.hpp"

#include <string>
#include <vector>

namespace brickyard::track {

struct BankSpec {
  std::string mode = "none";          // none | constant | curvature | segments | file (the track file's bank_deg column)
  double degrees = 0;                 // constant and curvature modes
  double curvature_threshold = 0.002;  // 1/m: a point is in a turn above this (curvature mode)
  double transition_m = 100;          // m over which the bank ramps in and out
  struct Range { double s0, s1, degrees; };
  std::vector<Range> segments;        // segments mode
};

// Bank angle per point (rad, positive raises the left edge). Positive degrees raise the outside:
// of each turn in curvature mode, of the loop (the right side of a counter-clockwise loop) in the
// constant and segments modes.
std::vector<double> bank_profile(const CenterLine& line, const BankSpec& spec);

}  // namespace brickyard::track
