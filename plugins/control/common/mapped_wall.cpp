#include "mapped_wall.hpp"

#include "math/polynomial.hpp"
#include "track/curvature.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::control {

std::vector<EdgePoint> mapped_edge(const track::Track& track, int side, double px, double py, double yaw, double behind,
                                   double ahead, int& hint) {
  std::vector<EdgePoint> out;
  const int n = track.size();
  if (n < 4) return out;
  const track::Frenet f = track.project(px, py, hint);
  hint = f.seg;
  const auto& seg = track.segments();
  const auto& line = track.geometry().line;
  // From the first point at least `behind` back to the first at least `ahead` on (`at`: a
  // point's distance along the line from the car's place); never more than one lap.
  int i = f.seg;
  double at = -f.u * seg[i].length;
  for (int k = 0; k < n && at > -behind; ++k) {
    i = track.wrap(i - 1);
    at -= seg[i].length;
  }
  for (int k = 0; k < n && at <= ahead; ++k, at += seg[i].length, i = track.wrap(i + 1)) {
    // The normal at a point: the mean of its two segments'.
    Eigen::Vector2d nrm = seg[track.wrap(i - 1)].n + seg[i].n;
    nrm = nrm.norm() > 1e-9 ? nrm.normalized() : seg[i].n;
    const double w = side > 0 ? line.width_left[i] : -line.width_right[i];
    out.push_back({line.x[i] + w * nrm.x(), line.y[i] + w * nrm.y()});
  }
  return in_vehicle_frame(std::move(out), px, py, yaw);
}

EdgeRegistration register_edge(const std::vector<EdgePoint>& edge, const WallView& wall, const RegistrationParams& p) {
  EdgeRegistration r;
  if (!wall.valid || wall.coefficients.empty()) return r;
  const double lo = std::max(p.from, wall.x_min), hi = std::min(p.to, wall.x_max);
  if (hi - lo < 2.0) return r;
  // Samples every metre along the edge's segments within the stretch: residual y_wall - y_edge.
  // Only the edge's first pass through the stretch: round a hairpin the edge of the way back
  // comes into the same x range again.
  double sx = 0, sr = 0, sxx = 0, sxr = 0, srr = 0;
  int m = 0;
  bool entered = false, left = false;
  for (std::size_t i = 0; i + 1 < edge.size() && !left; ++i) {
    const EdgePoint a = edge[i], b = edge[i + 1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const int steps = std::max(1, static_cast<int>(len));
    for (int k = 0; k < steps; ++k) {
      const double u = static_cast<double>(k) / steps, x = a.x + u * (b.x - a.x), y = a.y + u * (b.y - a.y);
      if (x < lo || x > hi) {
        left = entered;
        if (left) break;
        continue;
      }
      entered = true;
      const double res = math::poly_value(wall.coefficients, x) - y;
      sx += x, sr += res, sxx += x * x, sxr += x * res, srr += res * res;
      ++m;
    }
  }
  r.points = m;
  if (m < p.min_points) return r;
  // res = shift + slope x, least squares (a turn about the car moves the edge's y by about turn x).
  const double det = m * sxx - sx * sx;
  const double slope = std::abs(det) > 1e-9 ? (m * sxr - sx * sr) / det : 0.0;
  r.shift = (sr - slope * sx) / m;
  r.turn = std::atan(slope);
  const double sse = srr - 2 * r.shift * sr - 2 * slope * sxr + m * r.shift * r.shift + 2 * r.shift * slope * sx + slope * slope * sxx;
  r.rms = std::sqrt(std::max(sse, 0.0) / m);
  r.ok = std::abs(r.shift) <= p.max_shift && std::abs(r.turn) <= p.max_turn && r.rms <= p.max_rms;
  return r;
}

std::vector<EdgePoint> smoothed(const std::vector<EdgePoint>& line, double step, double half) {
  std::vector<EdgePoint> even;
  if (line.size() < 2 || step <= 0) return line;
  // Every `step` metres along the polyline...
  double next = 0, at = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const EdgePoint a = line[i], b = line[i + 1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) continue;
    for (; next <= at + len; next += step) {
      const double u = (next - at) / len;
      even.push_back({a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)});
    }
    at += len;
  }
  if (at - (next - step) > 0.5 * step) even.push_back(line.back());
  // ...then each the mean of its neighbours within `half` (fewer at the ends, symmetrically).
  const int n = static_cast<int>(even.size()), k = static_cast<int>(half / step);
  std::vector<EdgePoint> out(n);
  for (int i = 0; i < n; ++i) {
    const int w = std::min({k, i, n - 1 - i});
    double sx = 0, sy = 0;
    for (int j = i - w; j <= i + w; ++j) sx += even[j].x, sy += even[j].y;
    out[i] = {sx / (2 * w + 1), sy / (2 * w + 1)};
  }
  return out;
}

std::vector<double> chord_curvature(const std::vector<EdgePoint>& line, double span) {
  const int n = static_cast<int>(line.size());
  std::vector<double> along(n, 0.0), k(n, NAN);
  for (int i = 1; i < n; ++i) along[i] = along[i - 1] + std::hypot(line[i].x - line[i - 1].x, line[i].y - line[i - 1].y);
  int lo = 0, hi = 0;
  for (int i = 0; i < n; ++i) {
    while (lo + 1 < i && along[i] - along[lo + 1] >= span) ++lo;  // the last point at least `span` back
    hi = std::max(hi, i);
    while (hi < n - 1 && along[hi] - along[i] < span) ++hi;       // the first at least `span` on
    if (along[i] - along[lo] >= span && along[hi] - along[i] >= span)
      k[i] = track::menger_curvature(line[lo].x, line[lo].y, line[i].x, line[i].y, line[hi].x, line[hi].y);
  }
  // The ends, where no chord fits: their nearest point's (0 for a line too short for any).
  int first = 0;
  while (first < n && std::isnan(k[first])) ++first;
  if (first == n) return std::vector<double>(n, 0.0);
  for (int i = 0; i < first; ++i) k[i] = k[first];
  for (int i = first + 1; i < n; ++i)
    if (std::isnan(k[i])) k[i] = k[i - 1];
  return k;
}

std::vector<PathPoint> offset_polyline(const std::vector<EdgePoint>& polyline, int side, double gap, double v_cap,
                                       const WallLineParams& p) {
  // The map's points come every 5 m with their widths' noise: resampled every p.step and
  // averaged over p.smooth_half each side, so the tracker's heading and curvature are smooth.
  const std::vector<EdgePoint> wall = smoothed(polyline, p.step, p.smooth_half);
  const int n = static_cast<int>(wall.size());
  std::vector<PathPoint> line;
  if (n < 3) return line;
  // The gap each point allows: where the wall bends away from the car (the outside of a turn,
  // side * kappa < 0) the line inside it has curvature a / (1 - a g); keep that within
  // max_curvature. The gap changes by at most `taper` m per metre, so the line has no kink.
  constexpr double taper = 0.1;
  std::vector<double> g(n, std::clamp(gap, p.min_gap, std::max(p.min_gap, p.max_gap))), along(n, 0.0);
  for (int i = 1; i < n; ++i) along[i] = along[i - 1] + std::hypot(wall[i].x - wall[i - 1].x, wall[i].y - wall[i - 1].y);
  // Curvatures over chords of `kSpan` metres each side: the map's 5 m polygon leaves a ripple
  // that shorter chords read as sharp turns.
  constexpr double kSpan = 5.0;
  const std::vector<double> kw = chord_curvature(wall, kSpan);
  for (int i = 0; i < n; ++i) {
    const double a = -side * kw[i];
    if (a > 1e-6 && p.max_curvature > 0) g[i] = std::max(p.min_gap, std::min(g[i], 1.0 / a - 1.0 / p.max_curvature));
  }
  for (int i = n - 2; i >= 0; --i) g[i] = std::min(g[i], g[i + 1] + taper * (along[i + 1] - along[i]));
  for (int i = 1; i < n; ++i) g[i] = std::min(g[i], g[i - 1] + taper * (along[i] - along[i - 1]));
  for (int i = 0; i < n; ++i) {
    const EdgePoint a = wall[std::max(i - 1, 0)], b = wall[std::min(i + 1, n - 1)];
    const double len = std::max(std::hypot(b.x - a.x, b.y - a.y), 1e-9);
    const double tx = (b.x - a.x) / len, ty = (b.y - a.y) / len, left = -side * g[i];
    line.push_back({wall[i].x - left * ty, wall[i].y + left * tx, v_cap});
  }
  std::vector<EdgePoint> pts(n);
  for (int i = 0; i < n; ++i) pts[i] = {line[i].x, line[i].y};
  const std::vector<double> kl = chord_curvature(pts, kSpan);
  for (int i = 0; i < n; ++i)
    if (std::abs(kl[i]) > 1e-9 && p.a_lat > 0) line[i].speed = std::min(v_cap, std::sqrt(p.a_lat / std::abs(kl[i])));
  return line;
}

}  // namespace brickyard::control
