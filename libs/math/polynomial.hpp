#pragma once
// Polynomials as coefficient vectors, shared by perception and control (framework-free, header-only).
#include <cstddef>
#include <vector>

namespace brickyard::math {

// y of the polynomial c0 + c1 x + c2 x^2 + ... at x, or its first or second derivative.
inline double poly_value(const std::vector<double>& c, double x, int derivative = 0) {
  double y = 0;
  for (std::size_t k = c.size(); k-- > static_cast<std::size_t>(derivative);) {
    double f = c[k];
    for (int d = 0; d < derivative; ++d) f *= static_cast<double>(k - d);
    y = y * x + f;
  }
  return y;
}

}  // namespace brickyard::math
