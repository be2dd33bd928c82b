#include "track.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace brickyard::track {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

Track::Track(TrackGeometry geometry) : geo_(std::move(geometry)) {
  const auto& c = geo_.line;
  const int n = static_cast<int>(c.x.size());
  if (n < 4 || c.y.size() != c.x.size() || c.width_left.size() != c.x.size() || c.width_right.size() != c.x.size())
    throw std::invalid_argument("track needs at least 4 points with x, y and both widths");
  if (geo_.bank.empty()) geo_.bank.assign(n, 0.0);
  if (static_cast<int>(geo_.bank.size()) != n) throw std::invalid_argument("bank profile has the wrong length");
  seg_.resize(n);
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    Segment& s = seg_[i];
    s.p = {c.x[i], c.y[i]};
    Eigen::Vector2d e(c.x[j] - c.x[i], c.y[j] - c.y[i]);
    s.length = e.norm();
    if (s.length <= 0) throw std::invalid_argument("track has a zero-length segment at point " + std::to_string(i));
    s.t = e / s.length;
    s.n = {-s.t.y(), s.t.x()};
    s.s0 = length_;
    length_ += s.length;
  }
  ccw_ = track::counter_clockwise(c);
}

double Track::wrap_s(double s) const {
  s = std::fmod(s, length_);
  return s < 0 ? s + length_ : s;
}

double Track::lerp(const std::vector<double>& v, int seg, double u) const {
  u = std::clamp(u, 0.0, 1.0);
  return v[seg] + (v[wrap(seg + 1)] - v[seg]) * u;
}

double Track::bank(int seg, double u) const { return lerp(geo_.bank, seg, u); }
double Track::width_left(int seg, double u) const { return lerp(geo_.line.width_left, seg, u); }
double Track::width_right(int seg, double u) const { return lerp(geo_.line.width_right, seg, u); }

double Track::road_z(const Frenet& f) const {
  double d = std::clamp(f.d, -width_right(f.seg, f.u), width_left(f.seg, f.u));
  return d * std::tan(bank(f.seg, f.u));
}

Eigen::Vector2d Track::road_gradient(const Frenet& f) const {
  if (f.d > width_left(f.seg, f.u) || f.d < -width_right(f.seg, f.u)) return Eigen::Vector2d::Zero();
  return std::tan(bank(f.seg, f.u)) * seg_[f.seg].n;
}

Frenet Track::project_on(int i, double x, double y) const {
  const Segment& s = seg_[i];
  Eigen::Vector2d q(x - s.p.x(), y - s.p.y());
  Frenet f;
  f.seg = i;
  f.u = q.dot(s.t) / s.length;
  f.d = q.dot(s.n);
  f.s = wrap_s(s.s0 + f.u * s.length);
  return f;
}

Frenet Track::project(double x, double y, int hint) const {
  // The nearest segment: distance to the segment with u clamped to [0, 1].
  auto dist2 = [&](const Frenet& f) {
    const Segment& s = seg_[f.seg];
    double u = std::clamp(f.u, 0.0, 1.0);
    Eigen::Vector2d c = s.p + s.t * (u * s.length);
    return (Eigen::Vector2d(x, y) - c).squaredNorm();
  };
  auto search = [&](int from, int count) {
    Frenet best;
    double bd = kInf;
    for (int k = 0; k < count; ++k) {
      Frenet f = project_on(wrap(from + k), x, y);
      double dd = dist2(f);
      if (dd < bd) { bd = dd; best = f; }
    }
    return std::pair(best, bd);
  };
  if (hint >= 0) {
    auto [f, dd] = search(hint - 4, 9);
    // Trust the local answer when it lies inside its segment's slab, away from the window's ends.
    if (f.u >= -1e-9 && f.u <= 1 + 1e-9 && f.seg != wrap(hint - 4) && f.seg != wrap(hint + 4)) return f;
  }
  return search(0, size()).first;
}

Frenet Track::at(double s, double d) const {
  s = wrap_s(s);
  auto it = std::upper_bound(seg_.begin(), seg_.end(), s, [](double v, const Segment& g) { return v < g.s0; });
  int i = static_cast<int>(it - seg_.begin()) - 1;
  i = std::clamp(i, 0, size() - 1);
  Frenet f;
  f.seg = i;
  f.u = (s - seg_[i].s0) / seg_[i].length;
  f.s = s;
  f.d = d;
  return f;
}

Eigen::Vector2d Track::position(const Frenet& f) const {
  const Segment& s = seg_[f.seg];
  return s.p + s.t * (f.u * s.length) + s.n * f.d;
}

double Track::heading(const Frenet& f) const { return std::atan2(seg_[f.seg].t.y(), seg_[f.seg].t.x()); }

}  // namespace brickyard::track
