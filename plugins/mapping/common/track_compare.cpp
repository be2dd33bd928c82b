#include "track_compare.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

namespace {

struct Edges {
  std::vector<Eigen::Vector2d> centre, tangent, left, right;
};

Edges edges_of(const track::CenterLine& c) {
  Edges e;
  const std::size_t n = c.x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, b = (i + 1) % n;
    const Eigen::Vector2d t = Eigen::Vector2d(c.x[b] - c.x[a], c.y[b] - c.y[a]).normalized();
    const Eigen::Vector2d p(c.x[i], c.y[i]), nl(-t.y(), t.x());
    e.centre.push_back(p);
    e.tangent.push_back(t);
    e.left.push_back(p + nl * c.width_left[i]);
    e.right.push_back(p - nl * c.width_right[i]);
  }
  return e;
}

// The distance from q to the closed polyline, and the index and fraction of its nearest segment.
double to_polyline(const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& line, std::size_t* seg = nullptr,
                   double* frac = nullptr) {
  double best = INFINITY;
  const std::size_t n = line.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = line[i], ab = line[(i + 1) % n] - a;
    const double f = std::clamp(ab.squaredNorm() > 0 ? (q - a).dot(ab) / ab.squaredNorm() : 0.0, 0.0, 1.0);
    const double d = (a + f * ab - q).norm();
    if (d < best) {
      best = d;
      if (seg) *seg = i;
      if (frac) *frac = f;
    }
  }
  return best;
}

}  // namespace

ErrorStats error_stats(std::vector<double>& v) {
  ErrorStats s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto pct = [&](double p) {
    const double x = p * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(x);
    return i + 1 < v.size() ? v[i] + (x - static_cast<double>(i)) * (v[i + 1] - v[i]) : v[i];
  };
  s.p50 = pct(0.5);
  s.p95 = pct(0.95);
  s.max = v.back();
  return s;
}

TrackComparison compare_tracks(const track::CenterLine& mapped, const track::CenterLine& truth,
                               const std::vector<double>& truth_bank_rad) {
  TrackComparison out;
  const Edges m = edges_of(mapped), t = edges_of(truth);
  // Which way round: the mapped tangents against the truth's at the nearest centre points.
  int along = 0;
  std::vector<std::size_t> seg(m.centre.size());
  std::vector<double> frac(m.centre.size());
  for (std::size_t i = 0; i < m.centre.size(); ++i) {
    to_polyline(m.centre[i], t.centre, &seg[i], &frac[i]);
    along += m.tangent[i].dot(t.tangent[seg[i]]) >= 0 ? 1 : -1;
  }
  out.reversed = along < 0;
  const auto& t_left = out.reversed ? t.right : t.left;
  const auto& t_right = out.reversed ? t.left : t.right;
  std::vector<double> at_s(t.centre.size() + 1, 0.0);  // the truth's arc length at each point
  for (std::size_t i = 1; i <= t.centre.size(); ++i) at_s[i] = at_s[i - 1] + (t.centre[i % t.centre.size()] - t.centre[i - 1]).norm();
  std::vector<double> l, r, both, bank;
  double worst_edge = -1, worst_bank = -1;
  for (std::size_t i = 0; i < m.centre.size(); ++i) {
    l.push_back(to_polyline(m.left[i], t_left));
    r.push_back(to_polyline(m.right[i], t_right));
    both.push_back(l.back());
    both.push_back(r.back());
    const std::size_t a = seg[i], b = (a + 1) % t.centre.size();
    const double tb = (1 - frac[i]) * truth_bank_rad[a] + frac[i] * truth_bank_rad[b];
    const double mb = i < mapped.bank_deg.size() ? mapped.bank_deg[i] : 0.0;
    bank.push_back(std::abs(mb - (out.reversed ? -1 : 1) * tb * 180.0 / M_PI));
    const double here = at_s[a] + frac[i] * (at_s[a + 1] - at_s[a]);
    if (std::max(l.back(), r.back()) > worst_edge) worst_edge = std::max(l.back(), r.back()), out.edges_max_at_s = here;
    if (bank.back() > worst_bank) worst_bank = bank.back(), out.bank_max_at_s = here;
  }
  out.left = error_stats(l);
  out.right = error_stats(r);
  out.edges = error_stats(both);
  out.bank = error_stats(bank);
  return out;
}

}  // namespace brickyard::mapping
