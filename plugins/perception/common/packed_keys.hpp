#pragma once
// 32-bit cell keys for a cloud whose cells span few enough of them (any LiDAR frame): the voxel
// filter, the z-vote and the clustering hash these instead of cell_key's 64 bits when they fit.
#include "points.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

namespace brickyard::perception {

// The extent of a cloud and whether all of it is in range (finite, within kMaxCoordinate).
struct Box {
  float lo[3], hi[3];
  bool in_range;
};

// Four points (twelve floats, three vectors) at a time: lane k of a vector always holds axis k % 3.
// GCC and Clang vector types, so it is SSE2 on any x86-64 and vectorised elsewhere too.
inline Box box_of(const Points& in) {
  typedef float v4 __attribute__((vector_size(16)));
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float* f = in.empty() ? nullptr : in.data()->data();
  const std::size_t n = in.size();
  v4 lo[3], hi[3], nan[3];
  for (int k = 0; k < 3; ++k) lo[k] = v4{kInf, kInf, kInf, kInf}, hi[k] = -lo[k], nan[k] = v4{};
  std::size_t j = 0;
  for (; j + 4 <= n; j += 4)
    for (int k = 0; k < 3; ++k) {
      v4 v;
      std::memcpy(&v, f + 3 * j + 4 * k, sizeof v);
      lo[k] = v < lo[k] ? v : lo[k];
      hi[k] = v > hi[k] ? v : hi[k];
      nan[k] += v * 0.0f;  // stays 0 unless a NaN or an infinity passes (min/max would skip a NaN)
    }
  Box b{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}, true};
  float check = 0;
  for (int k = 0; k < 12; ++k) {
    b.lo[k % 3] = std::min(b.lo[k % 3], lo[k / 4][k % 4]);
    b.hi[k % 3] = std::max(b.hi[k % 3], hi[k / 4][k % 4]);
    check += nan[k / 4][k % 4];
  }
  for (; j < n; ++j)
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], f[3 * j + a]);
      b.hi[a] = std::max(b.hi[a], f[3 * j + a]);
      check += f[3 * j + a] * 0.0f;
    }
  b.in_range = n > 0 && check == 0;
  for (int a = 0; a < 3; ++a) b.in_range = b.in_range && b.lo[a] >= -kMaxCoordinate && b.hi[a] <= kMaxCoordinate;
  return b;
}

inline int bits_for(std::int64_t count) {
  int b = 0;
  while (b < 40 && (std::int64_t{1} << b) < count) ++b;
  return b;
}

// Cells lo..hi on each axis (the first `axes`; the others must be 0..0) numbered from lo and
// packed in 31 bits, the last axis lowest: half the key of cell_key, hashed with one multiply
// (cell_map.hpp), and never all ones (CellMap's empty slot). `ok` is false when the span does
// not fit; cells outside lo..hi would alias others.
struct Packing {
  std::int32_t lo[3] = {0, 0, 0};
  int shift[3] = {0, 0, 0};
  bool ok = false;
  Packing(const std::int32_t* lo_cell, const std::int32_t* hi_cell, int axes) {
    int bits = 0;
    for (int a = axes - 1; a >= 0; --a) {
      lo[a] = lo_cell[a];
      shift[a] = bits;
      bits += bits_for(std::int64_t{hi_cell[a]} - lo_cell[a] + 1);
    }
    ok = bits <= 31;
  }
  std::uint32_t key(std::int32_t x, std::int32_t y, std::int32_t z = 0) const {
    return static_cast<std::uint32_t>(x - lo[0]) << shift[0] | static_cast<std::uint32_t>(y - lo[1]) << shift[1] |
           static_cast<std::uint32_t>(z - lo[2]) << shift[2];
  }
};

// Every point's packed key on a grid of cell size 1 / inv_size (3 axes; the points must lie in
// the packing's cells). Four points at a time as in box_of: the cells of twelve floats in three
// vectors, as cell_of computes them (truncation corrected for negatives: a true compare is -1),
// less the packing's origin, then combined per point.
inline void packed_keys(const Points& in, float inv_size, const Packing& pk, std::uint32_t* keys) {
  typedef float v4 __attribute__((vector_size(16)));
  typedef std::int32_t v4i __attribute__((vector_size(16)));
  const float* f = in.empty() ? nullptr : in.data()->data();
  const std::size_t n = in.size();
  const v4i origin[3] = {{pk.lo[0], pk.lo[1], pk.lo[2], pk.lo[0]},
                         {pk.lo[1], pk.lo[2], pk.lo[0], pk.lo[1]},
                         {pk.lo[2], pk.lo[0], pk.lo[1], pk.lo[2]}};
  const v4 inv = {inv_size, inv_size, inv_size, inv_size};
  std::size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    std::uint32_t c[12];
    for (int k = 0; k < 3; ++k) {
      v4 v;
      std::memcpy(&v, f + 3 * j + 4 * k, sizeof v);
      v *= inv;
      const v4i t = __builtin_convertvector(v, v4i);
      const v4i cell = t + (v < __builtin_convertvector(t, v4)) - origin[k];
      std::memcpy(c + 4 * k, &cell, sizeof cell);
    }
    for (int p = 0; p < 4; ++p) keys[j + p] = c[3 * p] << pk.shift[0] | c[3 * p + 1] << pk.shift[1] | c[3 * p + 2] << pk.shift[2];
  }
  for (; j < n; ++j)
    keys[j] = pk.key(cell_of(f[3 * j], inv_size), cell_of(f[3 * j + 1], inv_size), cell_of(f[3 * j + 2], inv_size));
}

}  // namespace brickyard::perception
