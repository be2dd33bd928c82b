#include "follow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::planning {

double MovingCar::speed() const { return std::hypot(vx, vy); }

bool MovingCar::moving(const FollowParams& p) const { return length >= p.car_length && speed() - 2 * speed_sigma >= p.moving_speed; }

std::vector<Detection> not_moving_cars(const StampedPose& at, const std::vector<Detection>& list, const std::vector<MovingCar>& cars,
                                       const FollowParams& p) {
  std::vector<Detection> out;
  const double c = std::cos(at.yaw), s = std::sin(at.yaw);
  for (const Detection& d : list) {
    const double x = at.x + c * d.x - s * d.y, y = at.y + s * d.x + c * d.y;
    const bool a_car = std::any_of(cars.begin(), cars.end(), [&](const MovingCar& m) {
      return m.moving(p) && std::hypot(m.x - x, m.y - y) <= p.match_radius;
    });
    if (!a_car) out.push_back(d);
  }
  return out;
}

namespace {

constexpr double kReachTime = 6.0;   // s: how far ahead a car's way is looked at, at most
constexpr double kMinClosing = 0.5;  // m/s: closing slower than this counts as this

// Where (x, y) is along the path: the arc length to its nearest point, plus its projection on the
// path's direction there (the points are metres apart); its offset from the path there (left
// positive), and that point.
struct OnPath {
  double along = 0, offset = 0;
  std::size_t k = 0;
};
OnPath on_path(const std::vector<PathSample>& path, const std::vector<double>& arc, double x, double y) {
  std::size_t k = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < path.size(); ++i)
    if (const double d = std::hypot(path[i].x - x, path[i].y - y); d < best) best = d, k = i;
  const std::size_t a = k + 1 < path.size() ? k : k - 1;  // the segment from a to a + 1 gives the direction
  const double tx = path[a + 1].x - path[a].x, ty = path[a + 1].y - path[a].y, len = std::hypot(tx, ty);
  if (!(len > 0)) return {arc[k], best, k};
  const double u = ((x - path[k].x) * tx + (y - path[k].y) * ty) / len, n = ((y - path[k].y) * tx - (x - path[k].x) * ty) / len;
  return {arc[k] + u, n, k};
}

// Whether the path comes within `room` across of the car anywhere it will be while we close on
// it: the car holds its offset from the racing line (the path's d is the line's), from where it
// is on for as far as it goes in the time we take to reach it (at our speed less its, at most
// kReachTime), a car's length at least. A car on our line's far side now, where the line crosses
// over further on, is in our way.
bool in_the_way(const std::vector<PathSample>& path, const std::vector<double>& arc, const OnPath& at, const MovingCar& m,
                double gap, double our_speed, double room) {
  const double car_d = path[at.k].d + at.offset;
  const double closing = std::max(kMinClosing, our_speed - m.speed());
  const double reach = std::max(m.length, m.speed() * std::clamp(gap / closing, 0.0, kReachTime));
  for (std::size_t i = at.k; i < path.size() && arc[i] <= arc[at.k] + reach; ++i)
    if (std::abs(path[i].d - car_d) <= room) return true;
  return std::abs(at.offset) <= room;
}

}  // namespace

// The first moving car ahead of our bumper in the path's way.
double follow_speed(const std::vector<PathSample>& path, double x, double y, double our_speed, double front, double half_width,
                    const std::vector<MovingCar>& cars, const FollowParams& p, double* gap_out) {
  const double inf = std::numeric_limits<double>::infinity();
  if (gap_out) *gap_out = inf;
  if (path.size() < 2) return inf;
  std::vector<double> arc(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i) arc[i] = arc[i - 1] + std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  const double ours = on_path(path, arc, x, y).along;
  double cap = inf, nearest_gap = inf;
  for (const MovingCar& m : cars) {
    if (!m.moving(p)) continue;
    const OnPath at = on_path(path, arc, m.x, m.y);
    const double gap = at.along - ours - front - m.length / 2;
    if (gap < -m.length) continue;  // beside or behind us: not followed
    if (!in_the_way(path, arc, at, m, gap, our_speed, half_width + m.width / 2 + p.side_margin)) continue;
    const double wanted = p.min_gap + p.headway_s * m.speed();
    const double v = std::sqrt(m.speed() * m.speed() + 2 * p.decel * std::max(0.0, gap - wanted));
    const double v_cap = gap < wanted ? m.speed() * std::max(0.0, gap) / wanted : v;  // inside the gap: slower than it, to open it
    cap = std::min(cap, v_cap);
    nearest_gap = std::min(nearest_gap, gap);
  }
  if (gap_out) *gap_out = nearest_gap;
  return cap;
}

}  // namespace brickyard::planning
