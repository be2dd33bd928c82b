#include "banking.hpp"

#include "curvature.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brickyard::track {

std::vector<double> bank_profile(const CenterLine& c, const BankSpec& spec) {
  const int n = static_cast<int>(c.x.size());
  std::vector<double> target(n, 0.0);
  const double rad = spec.degrees * M_PI / 180.0;
  // The outside of a counter-clockwise loop is on the right: raising it lowers the left edge.
  const double loop_sign = counter_clockwise(c) ? -1.0 : 1.0;
  std::vector<double> s(n, 0.0);
  for (int i = 1; i < n; ++i) s[i] = s[i - 1] + std::hypot(c.x[i] - c.x[i - 1], c.y[i] - c.y[i - 1]);
  if (spec.mode == "none") return target;
  if (spec.mode == "file") {  // the track file's own column, as it was measured: no ramps added
    if (c.bank_deg.size() != c.x.size())
      throw std::invalid_argument(c.source + ": bank_mode 'file', but the track file has no bank_deg column");
    for (int i = 0; i < n; ++i) target[i] = c.bank_deg[i] * M_PI / 180.0;
    return target;
  }
  if (spec.mode == "constant") {
    target.assign(n, loop_sign * rad);
    return target;
  }
  if (spec.mode == "curvature") {
    auto k = signed_curvature(c, 50.0);
    for (int i = 0; i < n; ++i)
      if (std::abs(k[i]) > spec.curvature_threshold) target[i] = (k[i] > 0 ? -1.0 : 1.0) * rad;
  } else if (spec.mode == "segments") {
    for (const auto& r : spec.segments)
      for (int i = 0; i < n; ++i)
        if (s[i] >= r.s0 && s[i] < r.s1) target[i] = loop_sign * r.degrees * M_PI / 180.0;
  } else {
    throw std::invalid_argument("unknown bank mode '" + spec.mode + "'");
  }
  // Ramp in and out: a moving average over the transition length.
  double total = s[n - 1] + std::hypot(c.x[0] - c.x[n - 1], c.y[0] - c.y[n - 1]);
  // At most once round the loop: a ramp longer than the track is the track's mean, and (i + j + n)
  // stays a valid index.
  const int half = static_cast<int>(std::clamp(std::round(spec.transition_m / (total / n) / 2), 0.0, static_cast<double>(n)));
  if (half == 0) return target;
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int j = -half; j <= half; ++j) sum += target[(i + j + n) % n];
    out[i] = sum / (2 * half + 1);
  }
  return out;
}

}  // namespace brickyard::track
