#include "cloud/quantized_cloud.hpp"

#include <algorithm>
#include <limits>

namespace brickyard::cloud {
namespace {

constexpr double kMaxSteps = 2147483647.0;  // a coordinate's multiple of the precision fits an int32

}  // namespace

Quantized quantize(const std::vector<float>& x, const std::vector<float>& y, const std::vector<float>& z,
                   const std::vector<float>& intensity, double precision_m) {
  if (!(precision_m > 0 && precision_m <= 1)) throw std::invalid_argument("precision " + std::to_string(precision_m) + " m: expected (0, 1] m");
  const std::size_t n = x.size();
  if (y.size() != n || z.size() != n || (!intensity.empty() && intensity.size() != n))
    throw std::invalid_argument("x, y, z and intensity hold " + std::to_string(n) + ", " + std::to_string(y.size()) + ", " +
                                std::to_string(z.size()) + " and " + std::to_string(intensity.size()) + " values");
  Quantized q;
  q.precision_m = precision_m;
  q.steps.assign(12 * n, 0);
  std::int64_t prev[3] = {0, 0, 0};  // the previous point's steps (a point not finite repeats them)
  for (std::size_t i = 0; i < n; ++i) {
    const double s[3] = {std::nearbyint(x[i] / precision_m), std::nearbyint(y[i] / precision_m), std::nearbyint(z[i] / precision_m)};
    // Comparisons false for NaN: a point not finite, or beyond an int32 of steps, is said as such.
    if (!(std::abs(s[0]) <= kMaxSteps && std::abs(s[1]) <= kMaxSteps && std::abs(s[2]) <= kMaxSteps)) {
      q.not_finite.push_back(static_cast<std::uint32_t>(i));
      continue;  // its steps stay 0
    }
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::int64_t>(s[k]);
      // Two int32s' difference fits in 33 bits: kept modulo 2^32, as restore sums it.
      const auto d = static_cast<std::int32_t>(static_cast<std::uint32_t>(v - prev[k]));
      const std::uint32_t zig = (static_cast<std::uint32_t>(d) << 1) ^ static_cast<std::uint32_t>(d >> 31);
      for (int b = 0; b < 4; ++b) q.steps[(4 * k + b) * n + i] = static_cast<std::uint8_t>(zig >> (8 * b));
      prev[k] = v;
    }
  }
  if (!intensity.empty()) {
    float top = 0;
    for (float v : intensity)
      if (std::isfinite(v)) top = std::max(top, v);
    q.intensity_max = top;
    q.intensity.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const float v = intensity[i];
      q.intensity[i] = top > 0 && v > 0 && std::isfinite(v) ? static_cast<std::uint8_t>(std::lround(std::min(v / top, 1.0f) * 255.0f)) : 0;
    }
  }
  return q;
}

void restore(const Quantized& q, std::vector<float>& x, std::vector<float>& y, std::vector<float>& z, std::vector<float>& intensity) {
  if (!(q.precision_m > 0 && q.precision_m <= 1)) throw std::invalid_argument("precision_m " + std::to_string(q.precision_m) + ": expected (0, 1] m");
  if (q.steps.size() % 12 != 0) throw std::invalid_argument("steps hold " + std::to_string(q.steps.size()) + " bytes, not 12 a point");
  const std::size_t n = q.steps.size() / 12;
  if (!q.intensity.empty() && q.intensity.size() != n)
    throw std::invalid_argument("steps hold " + std::to_string(n) + " points and intensity " + std::to_string(q.intensity.size()));
  if (!(std::isfinite(q.intensity_max) && q.intensity_max >= 0)) throw std::invalid_argument("intensity_max is not a finite number >= 0");
  x.resize(n), y.resize(n), z.resize(n);
  std::vector<float>* out[3] = {&x, &y, &z};
  std::size_t k = 0;                        // the next not-finite index
  std::uint32_t sum[3] = {0, 0, 0};         // steps, summed modulo 2^32 as they were differenced
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < n; ++i) {
    if (k < q.not_finite.size() && q.not_finite[k] == i) {
      x[i] = y[i] = z[i] = nan;
      ++k;
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      std::uint32_t zig = 0;
      for (int b = 0; b < 4; ++b) zig |= static_cast<std::uint32_t>(q.steps[(4 * a + b) * n + i]) << (8 * b);
      sum[a] += (zig >> 1) ^ (0u - (zig & 1u));
      (*out[a])[i] = static_cast<float>(static_cast<double>(static_cast<std::int32_t>(sum[a])) * q.precision_m);
    }
  }
  if (k != q.not_finite.size())
    throw std::invalid_argument("not_finite lists point " + std::to_string(q.not_finite[k]) + " out of order or beyond the cloud's " +
                                std::to_string(n));
  intensity.resize(q.intensity.size());
  for (std::size_t i = 0; i < q.intensity.size(); ++i) intensity[i] = static_cast<float>(q.intensity[i]) / 255.0f * q.intensity_max;
}

}  // namespace brickyard::cloud
