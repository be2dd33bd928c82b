#pragma once
// Points for the perception algorithms, framework-free: plain float triples in the vehicle frame.
#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <vector>

namespace brickyard::perception {

using Point = Eigen::Vector3f;
using Points = std::vector<Point, Eigen::aligned_allocator<Point>>;

// Coordinates the algorithms take, m: a LiDAR sees a few hundred metres; beyond 10 km a cell's
// integer index could overflow. Points outside are dropped where clouds come in.
constexpr float kMaxCoordinate = 10000.0f;
// Not finite fails every comparison. Branch-free and small enough to inline in every loop over a
// cloud's points (as allFinite() and maxCoeff() it was a call per point: 4 % of a race's CPU).
inline bool in_range(const Point& p) {
  return (std::abs(p.x()) <= kMaxCoordinate) & (std::abs(p.y()) <= kMaxCoordinate) & (std::abs(p.z()) <= kMaxCoordinate);
}

// Integer cell of a point on a grid of the given size (floor division; truncation corrected for
// negatives, as std::floor is a library call without SSE4.1 and this runs for every point).
inline std::int32_t cell_of(float v, float inv_size) {
  const float f = v * inv_size;
  const auto t = static_cast<std::int32_t>(f);
  return t - (f < static_cast<float>(t));
}

// A 64-bit key of an (x, y, z) cell: 21 bits each (±1M cells: ±100 km at 0.1 m).
inline std::uint64_t cell_key(std::int32_t x, std::int32_t y, std::int32_t z) {
  constexpr std::uint64_t m = (1u << 21) - 1;
  return ((static_cast<std::uint64_t>(x) & m) << 42) | ((static_cast<std::uint64_t>(y) & m) << 21) | (static_cast<std::uint64_t>(z) & m);
}

}  // namespace brickyard::perception
