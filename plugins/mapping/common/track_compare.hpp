#pragma once
// How far a mapped track file is from the true one, framework-free: each mapped edge point
// (centre ± its normal × width) against the same edge of the truth as a closed polyline, and the
// mapped bank angle against the truth's at the nearest point of its centre line. Used by
// bench/eval_map_track and the tests; the car stack never has the truth.
#include "track/centre_line.hpp"

#include <cstddef>
#include <vector>

namespace brickyard::mapping {

struct ErrorStats {
  double p50 = 0, p95 = 0, max = 0;
  std::size_t n = 0;
};

struct TrackComparison {
  ErrorStats left, right, edges;  // m; edges: both sides together
  ErrorStats bank;                // degrees
  bool reversed = false;          // the mapped line runs the other way round (sides swapped)
  // Where the largest errors are: the truth's arc length (m from its first point) nearest the
  // mapped point with the largest edge error, and with the largest bank error.
  double edges_max_at_s = 0, bank_max_at_s = 0;
};

// truth_bank_rad: the truth's bank per point (track::bank_profile), positive raising the left edge;
// the mapped one is its bank_deg column (zero where it has none).
TrackComparison compare_tracks(const track::CenterLine& mapped, const track::CenterLine& truth,
                               const std::vector<double>& truth_bank_rad);

// The p50, p95 and largest of the values (sorted in place).
ErrorStats error_stats(std::vector<double>& values);

}  // namespace brickyard::mapping
