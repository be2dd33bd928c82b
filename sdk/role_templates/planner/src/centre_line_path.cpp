#include "centre_line_path.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace my_plugin {
namespace {

// Signed curvature through three points (Menger): positive turning left.
double curvature_through(double ax, double ay, double bx, double by, double cx, double cy) {
  const double cross = (bx - ax) * (cy - by) - (by - ay) * (cx - bx);
  const double ab = std::hypot(bx - ax, by - ay), bc = std::hypot(cx - bx, cy - by), ca = std::hypot(ax - cx, ay - cy);
  const double product = ab * bc * ca;
  return product > 0 ? 2 * cross / product : 0.0;
}

// The speed each point allows: its curvature's, then lowered so that the car can brake for the
// points after it.
void plan_speeds(std::vector<PathPoint>& path, const PathSettings& settings) {
  for (auto& p : path) {
    const double k = std::abs(p.curvature);
    p.speed = k > 0 ? std::min(settings.v_max, std::sqrt(settings.a_lat / k)) : settings.v_max;
  }
  for (std::size_t i = path.size(); i-- > 1;) {
    const double ds = path[i].s - path[i - 1].s;
    path[i - 1].speed = std::min(path[i - 1].speed, std::sqrt(path[i].speed * path[i].speed + 2 * settings.a_brake * ds));
  }
}

}  // namespace

CentreLinePath::CentreLinePath(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  if (x_.size() != y_.size()) throw std::invalid_argument("the centre line's x and y differ in size");
  if (x_.size() < 3) throw std::invalid_argument("the centre line needs at least 3 points");
  const std::size_t n = x_.size();
  curvature_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, c = next(i);
    curvature_[i] = curvature_through(x_[a], y_[a], x_[i], y_[i], x_[c], y_[c]);
  }
}

std::size_t CentreLinePath::nearest(double x, double y) const {
  std::size_t best = 0;
  for (std::size_t i = 1; i < x_.size(); ++i)
    if (std::hypot(x_[i] - x, y_[i] - y) < std::hypot(x_[best] - x, y_[best] - y)) best = i;
  return best;
}

std::vector<PathPoint> CentreLinePath::ahead_of(double car_x, double car_y, const PathSettings& settings) const {
  std::vector<PathPoint> path;
  std::size_t i = nearest(car_x, car_y);
  double s = 0;
  for (std::size_t count = 0; count <= x_.size() && (path.empty() || s < settings.ahead_m); ++count, i = next(i)) {
    const std::size_t j = next(i);
    if (!path.empty()) s += std::hypot(x_[i] - path.back().x, y_[i] - path.back().y);
    path.push_back({x_[i], y_[i], std::atan2(y_[j] - y_[i], x_[j] - x_[i]), curvature_[i], 0.0, s});
  }
  plan_speeds(path, settings);
  return path;
}

}  // namespace my_plugin
