#include "obstacles.hpp"

#include <Eigen/Eigenvalues>

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

// Thin across its best-fit plane, and that plane near the car's: the covariance's smallest
// eigenvalue and its eigenvector.
bool lies_flat(const Points& points, const std::vector<int>& c, const Eigen::Vector3f& centroid, const ObstacleParams& p) {
  Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
  for (int i : c) {
    const Eigen::Vector3f d = points[i] - centroid;
    cov += d * d.transpose();
  }
  cov /= static_cast<float>(c.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> eig(cov);
  const float thickness = std::sqrt(std::max(eig.eigenvalues()(0), 0.0f));
  const float normal_z = std::abs(eig.eigenvectors().col(0).z());
  return thickness < p.flat_thickness && normal_z > std::cos(static_cast<float>(p.flat_tilt_deg * M_PI / 180));
}

}  // namespace

std::vector<Obstacle> find_obstacles(const Points& points, const std::vector<std::vector<int>>& clusters,
                                     const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p) {
  std::vector<Obstacle> out;
  std::vector<char> wall_member(clusters.size(), 0);
  for (const auto& [w, side] : walls)
    for (int m : w.valid ? w.members : std::vector<int>{})
      if (m >= 0 && static_cast<std::size_t>(m) < clusters.size()) wall_member[m] = 1;
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    const auto& c = clusters[k];
    if (wall_member[k] || static_cast<int>(c.size()) < p.min_points) continue;
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
    if (std::abs(centroid.y()) > p.max_lateral || centroid.x() > p.max_range || centroid.x() < -p.max_behind) continue;
    if (size.x() > p.max_length || size.y() > p.max_length || size.z() < p.min_height) continue;
    if (c.size() >= 4 && lies_flat(points, c, centroid, p)) continue;
    out.push_back({centroid, size, c.size()});
  }
  return out;
}

}  // namespace brickyard::perception
