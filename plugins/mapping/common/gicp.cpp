#include "gicp.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace brickyard::mapping {

namespace {

// The target's points bucketed in cubes of the matching distance: a point's nearest within that
// distance is in its own cube or one of the 26 around it.
class NearestIndex {
 public:
  NearestIndex(const Points& pts, double radius) : pts_(pts), inv_(static_cast<float>(1.0 / radius)), r2_(radius * radius) {
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      if (perception::in_range(pts[i])) cells_[key(pts[i].cast<double>(), 0, 0, 0)].push_back(i);
  }
  // The index of the nearest point within the radius, or -1.
  long nearest(const Eigen::Vector3d& q) const {
    if (!q.allFinite() || q.cwiseAbs().maxCoeff() > perception::kMaxCoordinate) return -1;
    long best = -1;
    double best_d2 = r2_;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(q, dx, dy, dz));
          if (it == cells_.end()) continue;
          for (const std::uint32_t i : it->second) {
            const double d2 = (pts_[i].cast<double>() - q).squaredNorm();
            if (d2 < best_d2) best_d2 = d2, best = i;
          }
        }
    return best;
  }

 private:
  std::uint64_t key(const Eigen::Vector3d& q, int dx, int dy, int dz) const {
    const Point f = q.cast<float>();
    return perception::cell_key(perception::cell_of(f.x(), inv_) + dx, perception::cell_of(f.y(), inv_) + dy,
                                perception::cell_of(f.z(), inv_) + dz);
  }
  const Points& pts_;
  float inv_;
  double r2_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Whether b is within the epsilons of a.
bool within(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const PointRegistrationParams& p) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return d.translation().norm() < p.translation_eps && Eigen::AngleAxisd(d.linear()).angle() < p.rotation_eps;
}

struct Match {
  Eigen::Vector3d a, b;  // source point (source frame), its target point
  Eigen::Matrix3d weight;  // (C_b + R0 C_a R0^T)^-1
};

}  // namespace

RegistrationResult register_points(const Points& source, const Surfaces& source_surfaces, const Points& target,
                                   const Surfaces& target_surfaces, const Eigen::Isometry3d& guess,
                                   const PointRegistrationParams& p) {
  RegistrationResult out;
  out.transform = guess;
  if (source.size() != source_surfaces.size() || target.size() != target_surfaces.size()) return out;
  const NearestIndex index(target, p.max_correspondence_m);
  Eigen::Isometry3d T = guess;
  std::vector<Match> matches;
  std::vector<Eigen::Isometry3d> ends;  // where the rounds before the last ended
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  // The system and cost of the held matches at T: residual d = b - T a, its Jacobian over a turn
  // omega about the target's origin and a move v, [ [T a]x , -I ].
  auto linearize = [&](const Eigen::Isometry3d& at, Mat6& H, Vec6& g) {
    H.setZero();
    g.setZero();
    double cost = 0;
    for (const Match& m : matches) {
      const Eigen::Vector3d q = at * m.a, d = m.b - q;
      Eigen::Matrix<double, 3, 6> J;
      J << skew(q), -Eigen::Matrix3d::Identity();
      const Eigen::Matrix<double, 6, 3> JtW = J.transpose() * m.weight;
      H += JtW * J;
      g += JtW * d;
      cost += d.dot(m.weight * d);
    }
    return cost;
  };
  for (int round = 0; round < p.max_iterations; ++round) {
    // Matched at T, weighted with T's rotation.
    matches.clear();
    const Eigen::Matrix3d R0 = T.linear();
    for (std::size_t i = 0; i < source.size(); ++i) {
      if (!perception::in_range(source[i])) continue;
      const Eigen::Vector3d a = source[i].cast<double>();
      const long j = index.nearest(T * a);
      if (j < 0) continue;
      const Eigen::Matrix3d Ca = covariance_of(source_surfaces[i]).cast<double>();
      const Eigen::Matrix3d Cb = covariance_of(target_surfaces[j]).cast<double>();
      matches.push_back({a, target[j].cast<double>(), (Cb + R0 * Ca * R0.transpose()).inverse()});
    }
    out.matched = matches.size();
    if (matches.size() < 6) return out;  // the guess, not converged
    const Eigen::Isometry3d before = T;
    for (int k = 0; k < p.inner_iterations; ++k) {
      Mat6 H;
      Vec6 g;
      linearize(T, H, g);
      const Vec6 step = H.ldlt().solve(-g);
      if (!step.allFinite()) return out;
      // Left update: the turn about the origin, then the move.
      const Eigen::AngleAxisd turn(step.head<3>().norm(), step.head<3>().normalized());
      Eigen::Isometry3d next = Eigen::Isometry3d::Identity();
      if (step.head<3>().norm() > 0) next.linear() = turn.toRotationMatrix();
      next.translation() = step.tail<3>();
      T = next * T;
      if (step.head<3>().norm() < 0.1 * p.rotation_eps && step.tail<3>().norm() < 0.1 * p.translation_eps) break;
    }
    out.iterations = round + 1;
    if (within(before, T, p)) {
      out.converged = true;
      break;
    }
    // The matches can alternate: the pose comes back to where an earlier round (not the last)
    // ended, and no round will stand still (cuICP's pair in some frames: a cycle of two or
    // three rounds 0.4 mm apart). The loop has found its end there.
    const bool cycled = std::any_of(ends.begin(), ends.end(), [&](const Eigen::Isometry3d& e) { return within(e, T, p); });
    if (cycled) {
      out.converged = true;
      break;
    }
    ends.push_back(before);
  }
  Vec6 g;
  out.cost = linearize(T, out.hessian, g) / static_cast<double>(matches.size());
  out.transform = T;
  return out;
}

}  // namespace brickyard::mapping
