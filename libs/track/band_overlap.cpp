#include "band_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace brickyard::track {
namespace {

struct Vec {
  double x, y;
};
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y}; }
double cross(Vec a, Vec b) { return a.x * b.y - a.y * b.x; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y; }

// Parameter along a→b of the point of that segment nearest p.
double nearest_t(Vec a, Vec b, Vec p) {
  const Vec d = b - a;
  const double l2 = dot(d, d);
  return l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
}

bool proper_cross(Vec a, Vec b, Vec c, Vec d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Two stretches near each other: segments i and j, the nearest points of the two (ti, tj along the
// segments; si, sj along the loop), the distance between those, the widths that face each other
// there, and a crossing's angle.
struct Near {
  std::size_t i, j;
  double ti, tj, d, wi, wj, si, sj, angle_deg;
};

// The closed centre line as segments (segment i runs from point i to point i + 1), with the
// distance along the loop to each point and a grid of the cells each segment touches.
class Band {
 public:
  explicit Band(const CenterLine& c) : c_(c), n_(c.x.size()), arc_(n_ + 1, 0.0) {
    for (std::size_t i = 0; i < n_; ++i) {
      const Vec d = p(i + 1) - p(i);
      arc_[i + 1] = arc_[i] + std::hypot(d.x, d.y);
      max_w_ = std::max({max_w_, c.width_left[i], c.width_right[i]});
    }
    loop_ = arc_[n_];
    // Cells a little wider than the band, and no smaller than a mean segment, so that a segment
    // touches a few cells and a stretch's neighbours are in its own or the next.
    cell_ = std::max(2 * max_w_ + 1, loop_ / static_cast<double>(n_));
    for (std::size_t i = 0; i < n_; ++i) cells_of(i, 0, [&](std::uint64_t k) { grid_[k].push_back(static_cast<std::uint32_t>(i)); });
  }

  // Every pair of stretches nearer each other than their facing widths, or crossing.
  std::vector<Near> near_pairs() const {
    std::vector<Near> near;
    std::vector<std::uint32_t> seen;
    for (std::size_t i = 0; i < n_; ++i) {
      later_segments_near(i, seen);
      for (std::uint32_t j : seen) {
        if (j == i + 1 || (i == 0 && j == n_ - 1)) continue;  // segments that share a point
        if (const std::optional<Near> x = near_pair(i, j)) near.push_back(*x);
      }
    }
    return near;
  }

  double loop_gap(double s1, double s2) const {
    const double g = std::abs(s1 - s2);
    return std::min(g, loop_ - g);
  }

  BandOverlap as_overlap(const Near& x) const {
    return BandOverlap{x.ti < 0.5 ? x.i : (x.i + 1) % n_, x.tj < 0.5 ? x.j : (x.j + 1) % n_, x.d, x.wi + x.wj, x.angle_deg};
  }

 private:
  Vec p(std::size_t i) const { return Vec{c_.x[i % n_], c_.y[i % n_]}; }

  double width_at(std::size_t i, double t, bool left) const {
    const auto& w = left ? c_.width_left : c_.width_right;
    return (1 - t) * w[i % n_] + t * w[(i + 1) % n_];
  }

  static std::uint64_t key(std::int64_t cx, std::int64_t cy) {
    return static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(cy);
  }

  // Visits the key of each cell that segment i's bounding box, grown by `grow`, touches.
  template <typename Visit>
  void cells_of(std::size_t i, double grow, Visit&& visit) const {
    const Vec a = p(i), b = p(i + 1);
    const auto x0 = static_cast<std::int64_t>(std::floor((std::min(a.x, b.x) - grow) / cell_));
    const auto x1 = static_cast<std::int64_t>(std::floor((std::max(a.x, b.x) + grow) / cell_));
    const auto y0 = static_cast<std::int64_t>(std::floor((std::min(a.y, b.y) - grow) / cell_));
    const auto y1 = static_cast<std::int64_t>(std::floor((std::max(a.y, b.y) + grow) / cell_));
    for (auto cx = x0; cx <= x1; ++cx)
      for (auto cy = y0; cy <= y1; ++cy) visit(key(cx, cy));
  }

  // The segments after i in cells within two band widths of it, each once, in order.
  void later_segments_near(std::size_t i, std::vector<std::uint32_t>& seen) const {
    seen.clear();
    cells_of(i, 2 * max_w_, [&](std::uint64_t k) {
      auto it = grid_.find(k);
      if (it == grid_.end()) return;
      for (std::uint32_t j : it->second)
        if (j > i) seen.push_back(j);
    });
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  }

  // Segments i and j as a Near, when they cross or their bands meet.
  std::optional<Near> near_pair(std::size_t i, std::size_t j) const {
    const Vec a = p(i), b = p(i + 1);
    const Vec e = p(j), f = p(j + 1);
    // The two nearest points of the segments: on a crossing, the crossing; else an end of one
    // and its nearest point on the other.
    double ti = 0, tj = 0, d = 0, angle = 0;
    if (proper_cross(a, b, e, f)) {
      const double den = cross(b - a, f - e);
      ti = cross(e - a, f - e) / den;
      tj = cross(e - a, b - a) / den;
    } else {
      d = INFINITY;
      auto consider = [&](double si, double sj) {
        const Vec u{a.x + si * (b.x - a.x), a.y + si * (b.y - a.y)}, v{e.x + sj * (f.x - e.x), e.y + sj * (f.y - e.y)};
        const double dd = std::hypot(u.x - v.x, u.y - v.y);
        if (dd < d) { d = dd; ti = si; tj = sj; }
      };
      consider(0, nearest_t(e, f, a));
      consider(1, nearest_t(e, f, b));
      consider(nearest_t(a, b, e), 0);
      consider(nearest_t(a, b, f), 1);
    }
    const Vec qi{a.x + ti * (b.x - a.x), a.y + ti * (b.y - a.y)}, qj{e.x + tj * (f.x - e.x), e.y + tj * (f.y - e.y)};
    // Each stretch's width on the side that faces the other (at a crossing, or where one
    // passes through a point of the other, the wider side).
    const bool crossing = d < 1e-9;
    if (crossing) {
      d = 0;
      const Vec u = b - a, v = f - e;
      angle = std::acos(std::min(1.0, std::abs(dot(u, v)) / (std::hypot(u.x, u.y) * std::hypot(v.x, v.y)))) * 180 / M_PI;
    }
    const double wi = crossing ? std::max(width_at(i, ti, true), width_at(i, ti, false)) : width_at(i, ti, cross(b - a, qj - qi) > 0);
    const double wj = crossing ? std::max(width_at(j, tj, true), width_at(j, tj, false)) : width_at(j, tj, cross(f - e, qi - qj) > 0);
    if (!crossing && d >= wi + wj) return std::nullopt;
    return Near{i, j, ti, tj, d, wi, wj, arc_[i] + ti * (arc_[i + 1] - arc_[i]), arc_[j] + tj * (arc_[j + 1] - arc_[j]), angle};
  }

  const CenterLine& c_;
  std::size_t n_;
  std::vector<double> arc_;  // along the loop to each point; arc_[n_] is the loop's length
  double max_w_ = 0;
  double loop_ = 0;
  double cell_ = 0;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid_;  // cell key -> the segments touching it
};

// The crossings among the near pairs: the steep ones are bridges (into out.bridges, each once;
// returned), the first shallow one is an overlap (into out.overlap).
std::vector<Near> find_crossings(const Band& band, const std::vector<Near>& near, BandCheck& out) {
  std::vector<Near> bridges;
  for (const Near& x : near) {
    if (x.d != 0) continue;
    if (x.angle_deg >= kBridgeMinAngleDeg) {
      bool same = false;  // a crossing through a point of the line is found once per segment there
      for (const Near& br : bridges)
        same = same || (band.loop_gap(x.si, br.si) <= br.wi + br.wj && band.loop_gap(x.sj, br.sj) <= br.wi + br.wj) ||
               (band.loop_gap(x.si, br.sj) <= br.wi + br.wj && band.loop_gap(x.sj, br.si) <= br.wi + br.wj);
      if (same) continue;
      bridges.push_back(x);
      out.bridges.push_back(band.as_overlap(x));
    } else if (!out.overlap) {
      out.overlap = band.as_overlap(x);  // two stretches merged at a shallow angle: no bridge
    }
  }
  return bridges;
}

// Whether the pair x lies in a bridge's neighbourhood, where the two roads' bands overlap: as far
// along each road as the other's band reaches at that angle, and a band's width more.
bool at_a_bridge(const Band& band, const Near& x, const std::vector<Near>& bridges) {
  bool at_bridge = false;
  for (const Near& br : bridges) {
    const double reach = 2 * (br.wi + br.wj) / std::sin(br.angle_deg * M_PI / 180) + std::max(br.wi, br.wj);
    at_bridge = at_bridge || (band.loop_gap(x.si, br.si) <= reach && band.loop_gap(x.sj, br.sj) <= reach) ||
                (band.loop_gap(x.si, br.sj) <= reach && band.loop_gap(x.sj, br.si) <= reach);
  }
  return at_bridge;
}

// The worst of the pairs that do not cross, are not one bend and are away from the bridges.
void find_worst_overlap(const Band& band, const std::vector<Near>& near, const std::vector<Near>& bridges, BandCheck& out) {
  for (const Near& x : near) {
    if (x.d == 0 || band.loop_gap(x.si, x.sj) <= 3 * (x.wi + x.wj)) continue;
    if (at_a_bridge(band, x, bridges)) continue;
    if (!out.overlap || x.d - (x.wi + x.wj) < out.overlap->distance_m - out.overlap->widths_m) out.overlap = band.as_overlap(x);
  }
}

}  // namespace

BandCheck check_band(const CenterLine& c) {
  BandCheck out;
  if (c.x.size() < 4) return out;
  const Band band(c);
  // Every pair of stretches near each other, first; then the crossings among them, then the rest
  // away from the bridges.
  const std::vector<Near> near = band.near_pairs();
  const std::vector<Near> bridges = find_crossings(band, near, out);
  if (out.overlap) return out;
  find_worst_overlap(band, near, bridges, out);
  return out;
}

}  // namespace brickyard::track
