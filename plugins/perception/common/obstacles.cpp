#include "obstacles.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::perception {

namespace {

// The wall's y at x: the polynomial over the fitted extent, its tangent line beyond it (a
// polynomial extrapolated a hundred metres runs wild).
double wall_y_at(const WallFit& w, double x) {
  const double end = std::clamp(x, w.x_min, w.x_max);
  return poly_value(w.coefficients, end) + poly_value(w.coefficients, end, 1) * (x - end);
}

}  // namespace

std::vector<Obstacle> find_obstacles(const Points& points, const std::vector<std::vector<int>>& clusters,
                                     const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p) {
  std::vector<Obstacle> out;
  for (const auto& c : clusters) {
    if (static_cast<int>(c.size()) < p.min_points) continue;
    Eigen::Vector3f lo = points[c[0]], hi = points[c[0]], sum = Eigen::Vector3f::Zero();
    bool wall = false;
    for (int i : c) {
      const Point& q = points[i];
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
      sum += q;
      for (const auto& [w, side] : walls) {
        if (!w.valid) continue;
        // Signed distance inward from the wall at the point's height (the fitted lean included).
        const double wall_y = wall_y_at(w, q.x()) + w.lean * q.z();
        if ((wall_y - q.y()) * side < p.wall_margin) wall = true;
      }
    }
    if (wall) continue;
    const Eigen::Vector3f centroid = sum / static_cast<float>(c.size()), size = hi - lo;
    if (std::abs(centroid.y()) > p.max_lateral || std::abs(centroid.x()) > p.max_range) continue;
    if (size.x() > p.max_length || size.y() > p.max_length) continue;
    out.push_back({centroid, size, c.size()});
  }
  return out;
}

}  // namespace brickyard::perception
