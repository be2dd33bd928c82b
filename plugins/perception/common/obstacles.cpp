#include "obstacles.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::perception {

namespace {

// Where a wall is along x, at z = 0. The polynomial is fitted near the car only; far round a turn
// the wall is known from its points (the grown wall's clusters): 2 m bins of y - lean z, linear
// between bins and along the last 10 m's slope beyond them. Without points, the polynomial over
// its extent and its tangent beyond (a polynomial extrapolated a hundred metres runs wild).
class WallProfile {
 public:
  WallProfile(const WallFit& w, const Points& points, const std::vector<std::vector<int>>& clusters) : w_(w) {
    // Bins by index over the points' x range: one pass to find it, one to sum.
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (int m : w.members)
      if (m >= 0 && static_cast<std::size_t>(m) < clusters.size())
        for (int i : clusters[m]) {
          lo = std::min(lo, points[i].x());
          hi = std::max(hi, points[i].x());
        }
    if (!(lo <= hi) || hi - lo > 2 * kMaxCoordinate) return;  // nothing, or not points the algorithms take
    const int first = static_cast<int>(std::floor(lo / kBin)), last = static_cast<int>(std::floor(hi / kBin));
    std::vector<std::pair<double, int>> acc(static_cast<std::size_t>(last - first + 1), {0.0, 0});
    for (int m : w.members)
      if (m >= 0 && static_cast<std::size_t>(m) < clusters.size())
        for (int i : clusters[m]) {
          auto& a = acc[static_cast<std::size_t>(static_cast<int>(std::floor(points[i].x() / kBin)) - first)];
          a.first += points[i].y() - w.lean * points[i].z();
          ++a.second;
        }
    for (std::size_t b = 0; b < acc.size(); ++b)
      if (acc[b].second) bins_.emplace_back((first + static_cast<int>(b) + 0.5) * kBin, acc[b].first / acc[b].second);
  }
  // Whether x is within `reach` of where the wall is known: its bins, else the fit's extent.
  bool covers(double x, double reach) const {
    const double lo = bins_.size() >= 2 ? bins_.front().first - 0.5 * kBin : w_.x_min;
    const double hi = bins_.size() >= 2 ? bins_.back().first + 0.5 * kBin : w_.x_max;
    return x >= lo - reach && x <= hi + reach;
  }
  double y(double x) const {
    if (!std::isfinite(x)) return x;
    if (bins_.size() < 2) {
      const double end = w_.x_min <= w_.x_max ? std::clamp(x, w_.x_min, w_.x_max) : w_.x_min;
      return poly_value(w_.coefficients, end) + poly_value(w_.coefficients, end, 1) * (x - end);
    }
    if (x <= bins_.front().first) return extrapolate(x, 0, +1);
    if (x >= bins_.back().first) return extrapolate(x, bins_.size() - 1, -1);
    const auto hi = std::lower_bound(bins_.begin(), bins_.end(), std::pair{x, -1e300});
    const auto lo = std::prev(hi);
    const double t = (x - lo->first) / (hi->first - lo->first);
    return lo->second + t * (hi->second - lo->second);
  }

 private:
  static constexpr double kBin = 2.0;
  // From the end bin, along the slope to the bin about 10 m inward.
  double extrapolate(double x, std::size_t end, int inward) const {
    std::size_t k = end;
    while (k + inward < bins_.size() && std::abs(bins_[k].first - bins_[end].first) < 10.0) k += inward;
    const double slope = (bins_[end].second - bins_[k].second) / (bins_[end].first - bins_[k].first);
    return bins_[end].second + slope * (x - bins_[end].first);
  }
  const WallFit& w_;
  std::vector<std::pair<double, double>> bins_;  // (x centre, y), ascending x
};

// Thin across its best-fit plane, and that plane near the car's: the covariance's smallest
// eigenvalue and its eigenvector.
bool lies_flat(const Points& points, const std::vector<int>& c, const Eigen::Vector3f& centroid, const ObstacleParams& p) {
  Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
  for (int i : c) {
    const Eigen::Vector3f d = points[i] - centroid;
    cov += d * d.transpose();
  }
  cov /= static_cast<float>(c.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> eig(cov);
  const float thickness = std::sqrt(std::max(eig.eigenvalues()(0), 0.0f));
  const float normal_z = std::abs(eig.eigenvectors().col(0).z());
  return thickness < p.flat_thickness && normal_z > std::cos(static_cast<float>(p.flat_tilt_deg * M_PI / 180));
}

double walls_lean(const std::vector<std::pair<WallFit, int>>& walls, int side) {
  for (const auto& [w, s] : walls)
    if (s == side && w.valid) return w.lean;
  return 0;
}

// A candidate obstacle: one cluster, or clusters stacked at one place; `n` 0 once merged into another.
struct Part {
  Eigen::Vector3f lo, hi, sum;
  std::size_t n;
  std::vector<int> clusters;
};

// Whether q lies within wall_margin of a fitted wall or beyond it, where that counts as wall.
bool at_or_beyond_wall(const Point& q, const std::vector<std::pair<WallProfile, int>>& profiles,
                       const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p) {
  for (std::size_t v = 0; v < profiles.size(); ++v) {
    // Signed distance inward from the wall at the point's height (the fitted lean included).
    const auto& [profile, side] = profiles[v];
    const double wall_y = profile.y(q.x()) + walls_lean(walls, side) * q.z();
    const double inward = (wall_y - q.y()) * side;  // negative: beyond the wall
    if (inward < p.wall_margin && (profile.covers(q.x(), p.wall_reach) || inward > -p.wall_depth)) return true;
  }
  return false;
}

// Candidates: the clusters that are neither wall nor beyond it.
std::vector<Part> candidate_parts(const Points& points, const std::vector<std::vector<int>>& clusters,
                                  const std::vector<std::pair<WallFit, int>>& walls,
                                  const std::vector<std::pair<WallProfile, int>>& profiles, const std::vector<char>& wall_member,
                                  const ObstacleParams& p) {
  std::vector<Part> parts;
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    const auto& c = clusters[k];
    if (wall_member[k] || c.empty()) continue;
    Part part{points[c[0]], points[c[0]], Eigen::Vector3f::Zero(), c.size(), {static_cast<int>(k)}};
    bool wall = false;
    for (int i : c) {
      const Point& q = points[i];
      part.lo = part.lo.cwiseMin(q);
      part.hi = part.hi.cwiseMax(q);
      part.sum += q;
      if (!wall) wall = at_or_beyond_wall(q, profiles, walls, p);
    }
    if (!wall) parts.push_back(std::move(part));
  }
  return parts;
}

// Far off, the rows a thing is cut by land further apart than the clustering tolerance: a
// pylon at 60 m comes as two or three one-row streaks stacked at one place. Parts whose
// footprints overlap (within stack_gap) are one object: merged into the first of them.
void merge_stacked(std::vector<Part>& parts, const ObstacleParams& p) {
  std::vector<int> group(parts.size());
  for (std::size_t a = 0; a < parts.size(); ++a) group[a] = static_cast<int>(a);
  auto root = [&](int a) {
    while (group[a] != a) a = group[a] = group[group[a]];
    return a;
  };
  const float g = static_cast<float>(p.stack_gap);
  for (std::size_t a = 0; a < parts.size(); ++a)
    for (std::size_t b = a + 1; b < parts.size(); ++b) {
      const bool overlap = parts[a].lo.x() <= parts[b].hi.x() + g && parts[b].lo.x() <= parts[a].hi.x() + g &&
                           parts[a].lo.y() <= parts[b].hi.y() + g && parts[b].lo.y() <= parts[a].hi.y() + g;
      if (!overlap) continue;
      const int ra = root(static_cast<int>(a)), rb = root(static_cast<int>(b));
      if (ra != rb) group[std::max(ra, rb)] = std::min(ra, rb);
    }
  for (std::size_t a = 0; a < parts.size(); ++a) {
    const int r = root(static_cast<int>(a));
    if (r == static_cast<int>(a)) continue;
    Part& into = parts[r];
    into.lo = into.lo.cwiseMin(parts[a].lo);
    into.hi = into.hi.cwiseMax(parts[a].hi);
    into.sum += parts[a].sum;
    into.n += parts[a].n;
    into.clusters.insert(into.clusters.end(), parts[a].clusters.begin(), parts[a].clusters.end());
    parts[a].n = 0;
  }
}

// The corridor: within corridor_width of a fitted wall (it follows the wall round a turn),
// or within max_lateral of the car's axis when no wall is fitted.
bool in_corridor(const Eigen::Vector3f& centroid, const std::vector<std::pair<WallProfile, int>>& profiles, const ObstacleParams& p) {
  if (profiles.empty()) return !(std::abs(centroid.y()) > p.max_lateral);
  const auto& [profile, side] = profiles.front();
  return !((profile.y(centroid.x()) - centroid.y()) * side > p.corridor_width);
}

}  // namespace

// Andrew's monotone chain over the points sorted by x, then y.
std::vector<Eigen::Vector2f> footprint_hull(const Points& points, const std::vector<int>& members) {
  std::vector<Eigen::Vector2f> p;
  p.reserve(members.size());
  for (int i : members) p.emplace_back(points[i].x(), points[i].y());
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2f& a, const Eigen::Vector2f& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto cross = [](const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2f> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the first point again, last
  return hull;
}

namespace {
constexpr int kBoxMinPoints = 5;          // fewer: no fit
constexpr float kBoxMinExtent = 0.5f;     // m: a smaller footprint has no sides to speak of
constexpr float kBoxNear = 0.01f;         // m: closer to a side than this counts as on it
constexpr std::size_t kBoxSample = 256;   // points the fit takes at most

float box_closeness(const std::vector<Eigen::Vector2f>& p, float yaw) {
  const float c = std::cos(yaw), s = std::sin(yaw);
  float u0 = 1e30f, u1 = -1e30f, v0 = 1e30f, v1 = -1e30f;
  for (const auto& q : p) {
    const float u = c * q.x() + s * q.y(), v = -s * q.x() + c * q.y();
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
  }
  float score = 0;
  for (const auto& q : p) {
    const float u = c * q.x() + s * q.y(), v = -s * q.x() + c * q.y();
    score += 1.0f / std::max(std::min({u - u0, u1 - u, v - v0, v1 - v}), kBoxNear);
  }
  return score;
}
}  // namespace

float fitted_box_yaw(const Points& points, const std::vector<int>& members) {
  if (static_cast<int>(members.size()) < kBoxMinPoints) return std::numeric_limits<float>::quiet_NaN();
  // At most kBoxSample points, evenly through the obstacle: a near car's thousands cost a
  // hundred turns each, and its sides show in a few hundred as well.
  const std::size_t stride = std::max<std::size_t>(1, members.size() / kBoxSample);
  std::vector<Eigen::Vector2f> p;
  p.reserve(members.size() / stride + 1);
  Eigen::Vector2f lo(1e30f, 1e30f), hi(-1e30f, -1e30f);
  for (std::size_t k = 0; k < members.size(); k += stride) {
    p.emplace_back(points[members[k]].x(), points[members[k]].y());
    lo = lo.cwiseMin(p.back()), hi = hi.cwiseMax(p.back());
  }
  if ((hi - lo).maxCoeff() < kBoxMinExtent) return std::numeric_limits<float>::quiet_NaN();
  const float deg = static_cast<float>(M_PI / 180);
  float best = 0, best_score = -1;
  for (int k = 0; k < 90; ++k)
    if (const float sc = box_closeness(p, k * deg); sc > best_score) best_score = sc, best = k * deg;
  const float coarse = best;
  for (int k = -10; k <= 10; ++k)
    if (const float sc = box_closeness(p, coarse + k * 0.1f * deg); sc > best_score) best_score = sc, best = coarse + k * 0.1f * deg;
  const float quarter = static_cast<float>(M_PI / 2);
  return best - quarter * std::floor(best / quarter);
}

std::vector<Obstacle> find_obstacles(const Points& points, const std::vector<std::vector<int>>& clusters,
                                     const std::vector<std::pair<WallFit, int>>& walls, const ObstacleParams& p) {
  std::vector<Obstacle> out;
  std::vector<char> wall_member(clusters.size(), 0);
  std::vector<std::pair<WallProfile, int>> profiles;  // the valid walls
  for (const auto& [w, side] : walls) {
    if (!w.valid) continue;
    profiles.emplace_back(WallProfile(w, points, clusters), side);
    for (int m : w.members)
      if (m >= 0 && static_cast<std::size_t>(m) < clusters.size()) wall_member[m] = 1;
  }
  std::vector<Part> parts = candidate_parts(points, clusters, walls, profiles, wall_member, p);
  merge_stacked(parts, p);
  std::vector<int> members;
  for (const Part& part : parts) {
    if (part.n == 0 || static_cast<int>(part.n) < p.min_points) continue;
    const Eigen::Vector3f centroid = part.sum / static_cast<float>(part.n), size = part.hi - part.lo;
    if (centroid.x() > p.max_range || centroid.x() < -p.max_behind) continue;
    if (!in_corridor(centroid, profiles, p)) continue;
    if (size.x() > p.max_length || size.y() > p.max_length || size.z() < p.min_height) continue;
    members.clear();
    for (int c : part.clusters) members.insert(members.end(), clusters[c].begin(), clusters[c].end());
    if (members.size() >= 4 && lies_flat(points, members, centroid, p)) continue;
    out.push_back({centroid, size, part.n, footprint_hull(points, members), fitted_box_yaw(points, members)});
  }
  return out;
}

}  // namespace brickyard::perception
