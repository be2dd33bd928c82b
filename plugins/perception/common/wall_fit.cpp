#include "wall_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>

namespace brickyard::perception {

int longest_cluster_on_side(const Points& points, const std::vector<std::vector<int>>& clusters, int side, float near, float behind) {
  // Two candidates: the longest with a point where the wall is fitted (x in [-behind, near]), and
  // the longest of all, taken only when none has (a wall ahead beyond reach, grown back into it).
  // Why: standing at a chicane's exit, a stretch of wall 75-95 m behind the car outran the wall
  // beside it, and the fit, which takes no point that far back, found nothing to fit.
  int best_in = -1, best_any = -1;
  float len_in = -1, len_any = -1;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    if (clusters[c].empty()) continue;
    float xmin = std::numeric_limits<float>::max(), xmax = std::numeric_limits<float>::lowest(), ynear = 0;
    int n_near = 0, closest = clusters[c][0];
    bool in_window = false;
    for (int i : clusters[c]) {
      const Point& q = points[i];
      xmin = std::min(xmin, q.x());
      xmax = std::max(xmax, q.x());
      if (std::abs(q.x()) <= near) {
        ynear += q.y();
        ++n_near;
      }
      in_window = in_window || (q.x() <= near && q.x() >= -behind);
      if (std::abs(q.x()) < std::abs(points[closest].x())) closest = i;
    }
    // The side where the cluster passes the car: a long wall round a turn may have most of its
    // points across the car's axis further on.
    const float y = n_near ? ynear : points[closest].y();
    if (y * static_cast<float>(side) <= 0) continue;
    const float len = xmax - xmin;
    if (len > len_any) len_any = len, best_any = static_cast<int>(c);
    if (in_window && len > len_in) len_in = len, best_in = static_cast<int>(c);
  }
  return best_in >= 0 ? best_in : best_any;
}

namespace {

// Least squares y = sum_k s_k u^k (+ k z), u = (x - mid) / half: x is scaled to [-1, 1] over the
// points so the problem stays well conditioned at any degree. `sel` picks the points.
constexpr int kMaxTerms = 8;  // degree 6 and the lean: no heap in the fit

// With a `fixed_lean` the lean is not fitted but taken as given: y - fixed_lean z is fitted.
struct LocalFit {
  Eigen::VectorXd sol;
  double mid = 0, half = 1, rms = 0, fixed_lean = 0;
  int degree = 0;
  bool lean = false, ok = false;
  double lean_value() const { return lean ? sol(degree + 1) : fixed_lean; }
  double y(double x, double z) const {
    const double u = (x - mid) / half;
    double v = 0;
    for (int k = degree; k >= 0; --k) v = v * u + sol(k);
    return v + lean_value() * z;
  }
};

// The normal equations' sums for degree 2 without the lean (the growing wall's local fits, most
// of a frame's fits), in scalars: the general loop's arrays go through memory, where a
// store-to-load stall per term and point made that loop most of the wall fit's time. The same
// operations in the same order as the general loop, whose row is 1, u, u * u.
void quadratic_sums(const Points& pts, const std::vector<int>& sel, double fixed_lean, const LocalFit& f,
                    double (&ata)[kMaxTerms][kMaxTerms], double (&atb)[kMaxTerms], double& btb) {
  double a00 = 0, a10 = 0, a11 = 0, a20 = 0, a21 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, bb = 0;
  for (int i : sel) {
    const Point& q = pts[i];
    const double u = (q.x() - f.mid) / f.half, b = q.y() - fixed_lean * q.z(), u2 = u * u;
    a00 += 1.0;
    a10 += u;
    a11 += u * u;
    a20 += u2;
    a21 += u2 * u;
    a22 += u2 * u2;
    b0 += b;
    b1 += b * u;
    b2 += b * u2;
    bb += b * b;
  }
  ata[0][0] = a00, ata[1][0] = a10, ata[1][1] = a11, ata[2][0] = a20, ata[2][1] = a21, ata[2][2] = a22;
  atb[0] = b0, atb[1] = b1, atb[2] = b2;
  btb = bb;
}

LocalFit least_squares(const Points& pts, const std::vector<int>& sel, int degree, bool lean, double fixed_lean = 0) {
  LocalFit f;
  f.degree = degree;
  f.lean = lean;
  f.fixed_lean = fixed_lean;
  const int n = static_cast<int>(sel.size()), terms = degree + 1 + (lean ? 1 : 0);
  if (n < terms || terms > kMaxTerms) return f;
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (int i : sel) {
    lo = std::min(lo, static_cast<double>(pts[i].x()));
    hi = std::max(hi, static_cast<double>(pts[i].x()));
  }
  f.mid = 0.5 * (lo + hi);
  f.half = std::max(0.5 * (hi - lo), 1e-3);
  // Normal equations, accumulated without a design matrix: u in [-1, 1] keeps them well
  // conditioned at these degrees, and a frame makes dozens of these fits.
  double ata[kMaxTerms][kMaxTerms] = {}, atb[kMaxTerms] = {}, row[kMaxTerms];
  double btb = 0;
  if (degree == 2 && !lean) {
    quadratic_sums(pts, sel, fixed_lean, f, ata, atb, btb);
  } else {
    for (int i : sel) {
      const Point& q = pts[i];
      const double u = (q.x() - f.mid) / f.half, b = q.y() - (lean ? 0.0 : fixed_lean * q.z());
      double pw = 1;
      for (int k = 0; k <= degree; ++k, pw *= u) row[k] = pw;
      if (lean) row[degree + 1] = q.z();
      for (int a = 0; a < terms; ++a) {
        for (int c = 0; c <= a; ++c) ata[a][c] += row[a] * row[c];
        atb[a] += b * row[a];
      }
      btb += b * b;
    }
  }
  using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxTerms, kMaxTerms>;
  using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxTerms, 1>;
  Mat m(terms, terms);
  Vec v(terms);
  for (int a = 0; a < terms; ++a) {
    v(a) = atb[a];
    for (int c = 0; c <= a; ++c) m(a, c) = m(c, a) = ata[a][c];
  }
  f.sol = m.ldlt().solve(v);
  // Residual sum of squares from the same sums: |b|^2 - 2 s.A'b + s'A'A s.
  const double rss = btb - 2 * f.sol.dot(v) + f.sol.dot(m * f.sol);
  f.rms = std::sqrt(std::max(rss, 0.0) / n);
  f.ok = f.sol.allFinite();
  return f;
}

struct Extent {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
};

float far_end_of(const Extent& e, int dir) { return dir > 0 ? e.hi : e.lo; }

// Appends about 64 points of a cluster (evenly through it): the growing wall's local fits need
// its shape, not its thousands of points.
void add_sampled(const std::vector<int>& cluster, std::vector<int>& out) {
  const std::size_t stride = std::max<std::size_t>(1, cluster.size() / 64);
  for (std::size_t k = 0; k < cluster.size(); k += stride) out.push_back(cluster[k]);
}

// The x extent of each cluster.
std::vector<Extent> cluster_extents(const Points& points, const std::vector<std::vector<int>>& clusters) {
  std::vector<Extent> ext(clusters.size());
  for (std::size_t c = 0; c < clusters.size(); ++c)
    for (int i : clusters[c]) {
      ext[c].lo = std::min(ext[c].lo, points[i].x());
      ext[c].hi = std::max(ext[c].hi, points[i].x());
    }
  return ext;
}

// The wall grown from its longest cluster (w.cluster): the clusters that continue it past its
// ends, then those along it that were not joined. The lean is the car's roll, one value for the
// whole wall: taken from the longest cluster near the car and held fixed, so the short local fits
// need not find it (extrapolated up a wall seen from afar, a poorly found lean throws the fit off
// by metres).
class WallGrower {
 public:
  WallGrower(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p, WallFit& w)
      : points_(points), clusters_(clusters), p_(p), w_(w), ext_(cluster_extents(points, clusters)), member_(clusters.size(), 0),
        local_degree_(std::min(2, p.degree)) {
    member_[w.cluster] = 1;
    w.members = {w.cluster};
    lo_ = ext_[w.cluster].lo, hi_ = ext_[w.cluster].hi;
    if (p.lean) {
      std::vector<int> sel;
      for (int i : clusters[w.cluster])
        if (std::abs(points[i].x()) <= p.fit_range) sel.push_back(i);
      if (static_cast<int>(sel.size()) < 20) sel = clusters[w.cluster];
      const LocalFit seed = least_squares(points, sel, local_degree_, true);
      if (seed.ok) lean_ = seed.lean_value();
    }
    add_sampled(clusters[w.cluster], samples_);
  }

  // Grows the wall forward (+1) or backward (-1), one join_gap at a time, refitting the end each time.
  void grow(int dir) {
    // Each growing pass fits the samples within 30 m of the end; the end only moves outwards, so
    // a sample left behind stays behind: `live` drops it for good (in order) and takes a new
    // member's samples at its back, so a pass costs the wall's last 30 m, not its whole length.
    std::vector<int> live = samples_;
    for (int pass = 0; pass < 1000; ++pass)
      if (!grow_pass(dir, live)) break;
  }

  // Clusters within the wall's extent but not joined to it (a row's streak along the wall's foot
  // far round a turn): judged against the wall's piece where they are, fitted over 30 m.
  void join_within_extent() {
    const int pieces = static_cast<int>(std::min(std::ceil((hi_ - lo_) / 20.0f), 2000.0f));  // bounded: points are within 10 km
    std::vector<int> sel;
    for (int piece = 0; piece < pieces; ++piece) {
      const float b = lo_ + 20.0f * static_cast<float>(piece);
      sel.clear();
      for (int i : samples_)
        if (points_[i].x() >= b - 5.0f && points_[i].x() < b + 25.0f) sel.push_back(i);
      const LocalFit f = least_squares(points_, sel, local_degree_, false, lean_);
      if (!f.ok) continue;
      for (std::size_t c = 0; c < clusters_.size(); ++c) {
        if (member_[c] || ext_[c].hi < b || ext_[c].lo >= b + 20.0f || ext_[c].lo < lo_ || ext_[c].hi > hi_) continue;
        int on = 0;
        for (int i : clusters_[c]) on += std::abs(points_[i].y() - f.y(points_[i].x(), points_[i].z())) <= p_.join_margin;
        if (on * 10 < static_cast<int>(clusters_[c].size()) * 9) continue;
        member_[c] = 1;
        w_.members.push_back(static_cast<int>(c));
        add_sampled(clusters_[c], samples_);  // later pieces fit it too
      }
    }
  }

 private:
  // One growing pass from the end as it stands; whether it joined a cluster.
  bool grow_pass(int dir, std::vector<int>& live) {
    const float sgn = static_cast<float>(dir);
    float end = dir > 0 ? hi_ : lo_;
    const float fitted_end = end;
    live.erase(std::remove_if(live.begin(), live.end(), [&](int i) { return !((points_[i].x() - end) * sgn >= -30.0f); }), live.end());
    const LocalFit f = least_squares(points_, live, local_degree_, false, lean_);
    if (!f.ok) return false;
    // Candidates nearest first, each judged from the end as it stands then, so a stripe is
    // measured from the stripe before it, not from where the fit was made.
    find_candidates(dir, end);
    bool added = false;
    for (const auto& [gap, c] : candidates_) {
      if (member_[c] || (far_end_of(ext_[c], dir) - end) * sgn <= 0) continue;
      const float near_end = dir > 0 ? std::max(ext_[c].lo, end) : std::min(ext_[c].hi, end);
      if ((near_end - end) * sgn > p_.join_gap) break;
      if (!continues_wall(c, f, sgn, near_end, end, fitted_end)) continue;
      member_[c] = 1;
      w_.members.push_back(c);
      add_sampled(clusters_[c], samples_);
      add_sampled(clusters_[c], live);
      lo_ = std::min(lo_, ext_[c].lo);
      hi_ = std::max(hi_, ext_[c].hi);
      end = dir > 0 ? hi_ : lo_;
      added = true;
      if ((end - fitted_end) * sgn > 5.0f) break;  // refit before reaching further
    }
    return added;
  }

  // The clusters, not members, that reach past `end` and start within join_gap of it, nearest first.
  void find_candidates(int dir, float end) {
    const float sgn = static_cast<float>(dir);
    candidates_.clear();
    for (std::size_t c = 0; c < clusters_.size(); ++c) {
      if (member_[c]) continue;  // any side: far round a turn the wall crosses the car's axis
      const float near_end = dir > 0 ? ext_[c].lo : ext_[c].hi, far_end = dir > 0 ? ext_[c].hi : ext_[c].lo;
      if ((far_end - end) * sgn <= 0 || (near_end - end) * sgn > p_.join_gap) continue;
      candidates_.emplace_back((near_end - end) * sgn, static_cast<int>(c));
    }
    std::sort(candidates_.begin(), candidates_.end());
  }

  // Cluster c judged on its first 2 m past the end, against the local fit extrapolated there,
  // which is trusted less the further it reaches: nine in ten points within join_margin +
  // join_slope * (distance past the fit's end).
  bool continues_wall(int c, const LocalFit& f, float sgn, float near_end, float end, float fitted_end) const {
    int near = 0, on = 0;
    for (int i : clusters_[c]) {
      const float x = points_[i].x();
      if ((x - near_end) * sgn > 2.0f || (x - end) * sgn < 0) continue;
      ++near;
      const float past = (x - fitted_end) * sgn;
      on += std::abs(points_[i].y() - f.y(x, points_[i].z())) <= p_.join_margin + p_.join_slope * past;
    }
    return !(near == 0 || on * 10 < near * 9);
  }

  const Points& points_;
  const std::vector<std::vector<int>>& clusters_;
  const WallParams& p_;
  WallFit& w_;
  const std::vector<Extent> ext_;
  std::vector<char> member_;
  float lo_, hi_;  // the wall's x extent
  const int local_degree_;
  double lean_ = 0;
  std::vector<int> samples_;  // the members' samples, in member order
  std::vector<std::pair<float, int>> candidates_;
};

// The coefficients of sum_k sol_k ((x - mid)/half)^k expanded into powers of x.
std::vector<double> power_coefficients(const LocalFit& f, int degree) {
  std::vector<double> coefficients(degree + 1, 0.0);
  std::vector<double> term(1, 1.0);  // coefficients of ((x - mid)/half)^k in powers of x
  for (int k = 0; k <= degree; ++k) {
    for (std::size_t j = 0; j < term.size(); ++j) coefficients[j] += f.sol(k) * term[j];
    std::vector<double> next(term.size() + 1, 0.0);
    for (std::size_t j = 0; j < term.size(); ++j) {
      next[j + 1] += term[j] / f.half;
      next[j] -= term[j] * f.mid / f.half;
    }
    term = std::move(next);
  }
  return coefficients;
}

// The published fit: the wall's points near the car.
void fit_near_car(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p, WallFit& w) {
  std::vector<int> sel;
  for (int c : w.members)
    for (int i : clusters[c])
      if (points[i].x() <= p.fit_range && points[i].x() >= -p.fit_behind) sel.push_back(i);
  w.points = sel.size();
  const int terms = p.degree + 1 + (p.lean ? 1 : 0);
  if (static_cast<int>(sel.size()) < std::max(p.min_points, terms)) return;
  const LocalFit f = least_squares(points, sel, p.degree, p.lean);
  if (!f.ok) return;
  w.x_min = f.mid - f.half;
  w.x_max = f.mid + f.half;
  w.residual = f.rms;
  w.lean = p.lean ? f.sol(p.degree + 1) : 0.0;
  w.coefficients = power_coefficients(f, p.degree);
  w.distance = poly_value(w.coefficients, 0.0);
  const double d1 = poly_value(w.coefficients, p.lookahead, 1), d2 = poly_value(w.coefficients, p.lookahead, 2);
  w.heading = std::atan(d1);
  w.curvature = d2 / std::pow(1 + d1 * d1, 1.5);
  w.valid = w.x_max - w.x_min >= p.min_length && w.residual <= p.max_residual && std::isfinite(w.distance);
}

}  // namespace

WallFit fit_wall(const Points& points, const std::vector<std::vector<int>>& clusters, const WallParams& p) {
  WallFit w;
  w.cluster = longest_cluster_on_side(points, clusters, p.side, static_cast<float>(p.fit_range), static_cast<float>(p.fit_behind));
  if (w.cluster < 0) return w;
  WallGrower grower(points, clusters, p, w);
  for (int dir : {1, -1}) grower.grow(dir);
  grower.join_within_extent();
  fit_near_car(points, clusters, p, w);
  return w;
}

}  // namespace brickyard::perception
