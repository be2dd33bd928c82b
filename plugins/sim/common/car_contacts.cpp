#include "car_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::sim {

namespace {

double point_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double u = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + u * ab - p).norm();
}

// Whether an axis parts the two sets of corners (their projections do not overlap).
bool parts(const std::array<Eigen::Vector2d, 4>& p, const std::array<Eigen::Vector2d, 4>& q, const Eigen::Vector2d& axis) {
  double pmin = std::numeric_limits<double>::infinity(), pmax = -pmin, qmin = pmin, qmax = -pmin;
  for (const auto& v : p) pmin = std::min(pmin, v.dot(axis)), pmax = std::max(pmax, v.dot(axis));
  for (const auto& v : q) qmin = std::min(qmin, v.dot(axis)), qmax = std::max(qmax, v.dot(axis));
  return pmax < qmin || qmax < pmin;
}

}  // namespace

std::array<Eigen::Vector2d, 4> corners(const CarBox& c) {
  const Eigen::Vector2d o(c.x, c.y), f(std::cos(c.yaw), std::sin(c.yaw)), l(-f.y(), f.x());
  return {o + c.fp.front * f + c.fp.half_width * l, o - c.fp.rear * f + c.fp.half_width * l, o - c.fp.rear * f - c.fp.half_width * l,
          o + c.fp.front * f - c.fp.half_width * l};
}

bool cars_touch(const CarBox& a, const CarBox& b) {
  const auto p = corners(a), q = corners(b);
  for (const CarBox* c : {&a, &b}) {
    const Eigen::Vector2d f(std::cos(c->yaw), std::sin(c->yaw)), l(-f.y(), f.x());
    if (parts(p, q, f) || parts(p, q, l)) return false;
  }
  return true;
}

double car_gap(const CarBox& a, const CarBox& b) {
  if (cars_touch(a, b)) return 0.0;
  // Apart: the least distance is from a corner of one to an edge of the other.
  const auto p = corners(a), q = corners(b);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      best = std::min(best, point_to_segment(p[i], q[j], q[(j + 1) % 4]));
      best = std::min(best, point_to_segment(q[i], p[j], p[(j + 1) % 4]));
    }
  return best;
}

std::vector<int> CarContactBook::update(const CarBox& ours, const std::vector<std::optional<CarBox>>& others) {
  std::vector<int> began;
  touching_.resize(others.size(), false);
  for (std::size_t i = 0; i < others.size(); ++i) {
    if (!others[i]) continue;
    const double gap = car_gap(ours, *others[i]);
    min_gap_ = std::min(min_gap_, gap);
    const bool touch = gap == 0.0;
    if (touch && !touching_[i]) began.push_back(static_cast<int>(i)), ++contacts_;
    touching_[i] = touch;
  }
  return began;
}

}  // namespace brickyard::sim
