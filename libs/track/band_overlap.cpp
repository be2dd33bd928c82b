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

}  // namespace

BandCheck check_band(const CenterLine& c) {
  BandCheck out;
  const std::size_t n = c.x.size();
  if (n < 4) return out;
  auto p = [&](std::size_t i) { return Vec{c.x[i % n], c.y[i % n]}; };
  std::vector<double> arc(n + 1, 0.0);
  double max_w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec d = p(i + 1) - p(i);
    arc[i + 1] = arc[i] + std::hypot(d.x, d.y);
    max_w = std::max({max_w, c.width_left[i], c.width_right[i]});
  }
  const double loop = arc[n];
  // Cells a little wider than the band, and no smaller than a mean segment, so that a segment
  // touches a few cells and a stretch's neighbours are in its own or the next.
  const double cell = std::max(2 * max_w + 1, loop / static_cast<double>(n));
  auto key = [](std::int64_t cx, std::int64_t cy) { return static_cast<std::uint64_t>(cx) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(cy); };
  auto cells_of = [&](std::size_t i, double grow, auto&& visit) {
    const Vec a = p(i), b = p(i + 1);
    const auto x0 = static_cast<std::int64_t>(std::floor((std::min(a.x, b.x) - grow) / cell));
    const auto x1 = static_cast<std::int64_t>(std::floor((std::max(a.x, b.x) + grow) / cell));
    const auto y0 = static_cast<std::int64_t>(std::floor((std::min(a.y, b.y) - grow) / cell));
    const auto y1 = static_cast<std::int64_t>(std::floor((std::max(a.y, b.y) + grow) / cell));
    for (auto cx = x0; cx <= x1; ++cx)
      for (auto cy = y0; cy <= y1; ++cy) visit(key(cx, cy));
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t i = 0; i < n; ++i) cells_of(i, 0, [&](std::uint64_t k) { grid[k].push_back(static_cast<std::uint32_t>(i)); });

  auto width_at = [&](std::size_t i, double t, bool left) {
    const auto& w = left ? c.width_left : c.width_right;
    return (1 - t) * w[i % n] + t * w[(i + 1) % n];
  };
  // Every pair of stretches near each other, first; then the crossings among them, then the rest
  // away from the bridges.
  struct Near {
    std::size_t i, j;
    double ti, tj, d, wi, wj, si, sj, angle_deg;
  };
  std::vector<Near> near;
  std::vector<std::uint32_t> seen;
  for (std::size_t i = 0; i < n; ++i) {
    seen.clear();
    cells_of(i, 2 * max_w, [&](std::uint64_t k) {
      auto it = grid.find(k);
      if (it == grid.end()) return;
      for (std::uint32_t j : it->second)
        if (j > i) seen.push_back(j);
    });
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    const Vec a = p(i), b = p(i + 1);
    for (std::uint32_t j : seen) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // segments that share a point
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
      if (!crossing && d >= wi + wj) continue;
      near.push_back({i, j, ti, tj, d, wi, wj, arc[i] + ti * (arc[i + 1] - arc[i]), arc[j] + tj * (arc[j + 1] - arc[j]), angle});
    }
  }
  auto loop_gap = [&](double s1, double s2) {
    const double g = std::abs(s1 - s2);
    return std::min(g, loop - g);
  };
  auto as_overlap = [&](const Near& x) {
    return BandOverlap{x.ti < 0.5 ? x.i : (x.i + 1) % n, x.tj < 0.5 ? x.j : (x.j + 1) % n, x.d, x.wi + x.wj, x.angle_deg};
  };
  std::vector<Near> bridges;
  for (const Near& x : near) {
    if (x.d != 0) continue;
    if (x.angle_deg >= kBridgeMinAngleDeg) {
      bool same = false;  // a crossing through a point of the line is found once per segment there
      for (const Near& br : bridges)
        same = same || (loop_gap(x.si, br.si) <= br.wi + br.wj && loop_gap(x.sj, br.sj) <= br.wi + br.wj) ||
               (loop_gap(x.si, br.sj) <= br.wi + br.wj && loop_gap(x.sj, br.si) <= br.wi + br.wj);
      if (same) continue;
      bridges.push_back(x);
      out.bridges.push_back(as_overlap(x));
    } else if (!out.overlap) {
      out.overlap = as_overlap(x);  // two stretches merged at a shallow angle: no bridge
    }
  }
  if (out.overlap) return out;
  for (const Near& x : near) {
    if (x.d == 0 || loop_gap(x.si, x.sj) <= 3 * (x.wi + x.wj)) continue;
    // Around a bridge the two roads' bands overlap: as far along each road as the other's band
    // reaches at that angle, and a band's width more.
    bool at_bridge = false;
    for (const Near& br : bridges) {
      const double reach = 2 * (br.wi + br.wj) / std::sin(br.angle_deg * M_PI / 180) + std::max(br.wi, br.wj);
      at_bridge = at_bridge || (loop_gap(x.si, br.si) <= reach && loop_gap(x.sj, br.sj) <= reach) ||
                  (loop_gap(x.si, br.sj) <= reach && loop_gap(x.sj, br.si) <= reach);
    }
    if (at_bridge) continue;
    if (!out.overlap || x.d - (x.wi + x.wj) < out.overlap->distance_m - out.overlap->widths_m) out.overlap = as_overlap(x);
  }
  return out;
}

}  // namespace brickyard::track
