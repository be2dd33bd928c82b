#include "map_coverage.hpp"

#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace brickyard::mapping {

namespace {

std::int64_t cell_key(std::int64_t i, std::int64_t j) { return (i << 32) ^ (j & 0xffffffff); }

}  // namespace

double share_near_map(const Points& map, const std::vector<double>& x, const std::vector<double>& y, double reach) {
  if (x.empty()) return 0;
  std::unordered_set<std::int64_t> cells;
  for (const auto& p : map) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
    cells.insert(cell_key(static_cast<std::int64_t>(std::floor(p.x() / reach)), static_cast<std::int64_t>(std::floor(p.y() / reach))));
  }
  std::size_t near = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    const auto i = static_cast<std::int64_t>(std::floor(x[k] / reach)), j = static_cast<std::int64_t>(std::floor(y[k] / reach));
    bool found = false;
    for (std::int64_t di = -1; di <= 1 && !found; ++di)
      for (std::int64_t dj = -1; dj <= 1 && !found; ++dj) found = cells.count(cell_key(i + di, j + dj)) > 0;
    near += found;
  }
  return static_cast<double>(near) / static_cast<double>(x.size());
}

}  // namespace brickyard::mapping
