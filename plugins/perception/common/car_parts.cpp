#include "perception/common/car_parts.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace brickyard::perception {

namespace {

constexpr double kFitTurn = 30 * M_PI / 180;  // a heading seen further than this from the prior is not the car's
constexpr double kLooseAcross = 1.5;   // m more across for the first, loose grouping
constexpr double kClaimMargin = 0.5;   // m about a car's footprint within which what is left is its
constexpr double kWhole = 0.3;         // m: seen to within this of its length (width), a car is seen whole

// A detection in the frame turned by a heading: u along it, v across; the extent of its outline
// (its footprint's hull; a detection without one: its box's corners).
struct Part {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  double u() const { return 0.5 * (u0 + u1); }
  double v() const { return 0.5 * (v0 + v1); }
};

Part turned(const Detection& d, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Part p{1e300, -1e300, 1e300, -1e300};
  auto take = [&](double x, double y) {
    const double u = c * x + s * y, v = -s * x + c * y;
    p.u0 = std::min(p.u0, u), p.u1 = std::max(p.u1, u), p.v0 = std::min(p.v0, v), p.v1 = std::max(p.v1, v);
  };
  if (d.outline.empty())
    for (double sx : {-0.5, 0.5})
      for (double sy : {-0.5, 0.5}) take(d.x + sx * d.size_x, d.y + sy * d.size_y);
  for (const auto& q : d.outline) take(q.x(), q.y());
  return p;
}

double gap(const Part& a, const Part& b) {
  return std::hypot(std::max({0.0, b.u0 - a.u1, a.u0 - b.u1}), std::max({0.0, b.v0 - a.v1, a.v0 - b.v1}));
}

// The centre, (u, v), of the car whose parts make `box`, the sensor at (sensor_u, sensor_v). Along
// and across alike: what is seen spans the car (within kWhole), the middle of it; else the car is
// beyond its near end (the face seen is the one turned to the sensor); beside the sensor and seen
// in part, the middle of what is seen.
std::pair<double, double> car_centre(const Part& box, double sensor_u, double sensor_v, const CarShape& car) {
  auto centre = [](double lo, double hi, double size, double sensor) {
    if (hi - lo >= size - kWhole) return 0.5 * (lo + hi);
    if (lo > sensor) return lo + size / 2;
    if (hi < sensor) return hi - size / 2;
    return 0.5 * (lo + hi);
  };
  return {centre(box.u0, box.u1, car.length, sensor_u), centre(box.v0, box.v1, car.width, sensor_v)};
}

// The seed's group turned by th: nearest first, the parts not yet used that keep the union within
// a footprint (its width allowing `slack` more); marked used.
std::vector<int> gather(int seed, const std::vector<Part>& parts, const std::vector<int>& order, std::vector<char>& used,
                        const CarShape& car, double slack) {
  const double max_length = car.length + car.fit_margin, max_width = car.width + car.fit_margin + slack;
  std::vector<int> group{seed};
  used[seed] = 1;
  Part box = parts[seed];
  for (;;) {
    int best = -1;
    double best_gap = car.join_gap;
    for (int b : order) {
      if (used[b]) continue;
      const Part& o = parts[b];
      const double len = std::max(box.u1, o.u1) - std::min(box.u0, o.u0), wid = std::max(box.v1, o.v1) - std::min(box.v0, o.v0);
      const double g = gap(box, o);
      if (g <= best_gap && len <= max_length && wid <= max_width) best = b, best_gap = g;
    }
    if (best < 0) return group;
    used[best] = 1;
    group.push_back(best);
    const Part& o = parts[best];
    box.u0 = std::min(box.u0, o.u0), box.u1 = std::max(box.u1, o.u1), box.v0 = std::min(box.v0, o.v0), box.v1 = std::max(box.v1, o.v1);
  }
}

// The car's heading from what is seen of it: the sides of its largest part (the detector's fitted
// rectangle, a quarter turn either way) nearest the prior, when within kFitTurn of it. None when
// that part has no sides to speak of.
std::optional<double> seen_heading(const std::vector<Detection>& in, const std::vector<int>& group, double prior) {
  const Detection* largest = nullptr;
  for (int k : group)
    if (!largest || std::max(in[k].size_x, in[k].size_y) > std::max(largest->size_x, largest->size_y)) largest = &in[k];
  if (!largest || !std::isfinite(largest->box_yaw)) return std::nullopt;
  const double quarter = M_PI / 2;
  const double turn = largest->box_yaw + quarter * std::round((prior - largest->box_yaw) / quarter);
  if (std::abs(turn - prior) > kFitTurn) return std::nullopt;
  return turn;
}

}  // namespace

// Greedy, the largest detection first (a car's face gathers its side's stacks): its group found
// turned by its prior heading, loosely across (the prior may be degrees off); what is seen of the
// car then says its heading, and the group is found again turned by it, as tightly as a footprint
// allows.
std::vector<Detection> whole_cars(const std::vector<Detection>& in, const std::vector<PriorHeading>& prior, const CarShape& car) {
  std::vector<int> order(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::max(in[a].size_x, in[a].size_y) > std::max(in[b].size_x, in[b].size_y); });
  std::vector<char> used(in.size(), 0);
  std::vector<Detection> out;
  std::vector<Part> parts(in.size());
  auto turn_all = [&](double th) {
    for (std::size_t k = 0; k < in.size(); ++k) parts[k] = turned(in[k], th);
  };
  for (int a : order) {
    if (used[a]) continue;
    double th = prior[a].theta;
    turn_all(th);
    std::vector<int> group = gather(a, parts, order, used, car, kLooseAcross);
    if (const auto fitted = seen_heading(in, group, th); fitted && !prior[a].sure) th = *fitted;
    for (int k : group) used[k] = 0;
    turn_all(th);
    group = gather(a, parts, order, used, car, 0.0);
    Part box = parts[a];
    for (int k : group)
      box.u0 = std::min(box.u0, parts[k].u0), box.u1 = std::max(box.u1, parts[k].u1), box.v0 = std::min(box.v0, parts[k].v0),
      box.v1 = std::max(box.v1, parts[k].v1);
    if (std::max(box.u1 - box.u0, box.v1 - box.v0) < car.min_extent) {  // not a car: as the detector gave it
      for (int k : group) out.push_back(in[k]);
      continue;
    }
    const double c = std::cos(th), s = std::sin(th);
    const auto [u, v] = car_centre(box, c * car.sensor_x, -s * car.sensor_x, car);
    out.push_back({c * u - s * v, s * u + c * v, car.length, car.width});
    // Far off, a side's stacks land metres apart, further from the face than join_gap: those
    // within the car's footprint are its.
    for (std::size_t k = 0; k < in.size(); ++k)
      if (!used[k] && std::abs(parts[k].u() - u) <= car.length / 2 + kClaimMargin && std::abs(parts[k].v() - v) <= car.width / 2 + kClaimMargin)
        used[k] = 1;
  }
  return out;
}

}  // namespace brickyard::perception
