#include "vgicp.hpp"

#include <cmath>

namespace brickyard::mapping {

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

struct Linearized {
  Mat6 H = Mat6::Zero();
  Vec6 g = Vec6::Zero();
  double cost = 0;
  std::size_t matched = 0;
};

// The objective at T and, with `derivatives`, its Gauss-Newton system for a step exp(delta) T,
// delta = (rotation omega, translation v): e_i = mu_v - T a_i changes by [T a_i]x omega - v.
Linearized linearize(const Points& scan, const Covariances& covs, const VoxelMap& map, const Eigen::Isometry3d& T,
                     const RegistrationParams& p, bool derivatives) {
  Linearized out;
  const Eigen::Matrix3d R = T.linear();
  const double s = map.voxel_size();
  const Eigen::Vector3d offsets[7] = {{0, 0, 0}, {s, 0, 0}, {-s, 0, 0}, {0, s, 0}, {0, -s, 0}, {0, 0, s}, {0, 0, -s}};
  const int looks = p.face_neighbours ? 7 : 1;
  for (std::size_t i = 0; i < scan.size() && i < covs.size(); ++i) {
    const Eigen::Vector3d q = T * scan[i].cast<double>();
    const Eigen::Matrix3d rcr = R * covs[i].cast<double>() * R.transpose();
    bool any = false;
    for (int k = 0; k < looks; ++k) {
      const Voxel* v = map.at(q + offsets[k]);
      if (!v) continue;
      any = true;
      const Eigen::Vector3d e = v->mean() - q;
      const Eigen::Matrix3d W = p.weight * static_cast<double>(v->count) * (v->covariance() + rcr).inverse();
      if (!W.allFinite()) continue;
      const Eigen::Vector3d We = W * e;
      out.cost += e.dot(We);
      if (!derivatives) continue;
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = skew(q);
      J.rightCols<3>() = -Eigen::Matrix3d::Identity();
      out.H.noalias() += J.transpose() * W * J;
      out.g.noalias() += J.transpose() * We;
    }
    out.matched += any;
  }
  return out;
}

// The prior's term at T, added to L (see PosePrior): r changes by (omega, -[t]x omega + v).
void add_prior(const PosePrior& pr, const Eigen::Isometry3d& T, bool derivatives, Linearized& L) {
  Vec6 r;
  const Eigen::AngleAxisd turn(T.linear() * pr.mean.linear().transpose());
  r.head<3>() = turn.angle() * turn.axis();
  r.tail<3>() = T.translation() - pr.mean.translation();
  const Vec6 Lr = pr.information * r;
  L.cost += r.dot(Lr);
  if (!derivatives) return;
  Mat6 J = Mat6::Identity();
  J.bottomLeftCorner<3, 3>() = -skew(T.translation());
  L.H.noalias() += J.transpose() * pr.information * J;
  L.g.noalias() += J.transpose() * Lr;
}

Eigen::Isometry3d step(const Vec6& d, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d w = d.head<3>(), v = d.tail<3>();
  const double a = w.norm();
  const Eigen::Matrix3d dR = a > 0 ? Eigen::AngleAxisd(a, w / a).toRotationMatrix() : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = dR * T.linear();
  out.translation() = dR * T.translation() + v;
  return out;
}

}  // namespace

RegistrationResult register_scan(const Points& scan, const Covariances& covs, const VoxelMap& map,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p, const PosePrior* prior) {
  RegistrationResult r;
  r.transform = guess;
  double lambda = 1e-6;
  auto at = [&](const Eigen::Isometry3d& T, bool derivatives) {
    Linearized L = linearize(scan, covs, map, T, p, derivatives);
    if (prior) add_prior(*prior, T, derivatives, L);
    return L;
  };
  // Each trial point is linearized in full: a step that is taken needs no second pass at its
  // point (the trial's system is the next iteration's).
  Linearized L = at(r.transform, true);
  auto keep = [&](const Linearized& at_T) {
    r.hessian = at_T.H;
    r.matched = at_T.matched;
    r.cost = at_T.matched ? at_T.cost / static_cast<double>(at_T.matched) : 0;
  };
  keep(L);
  for (r.iterations = 0; r.iterations < p.max_iterations; ++r.iterations) {
    if (L.matched < 6) return r;
    // Levenberg-Marquardt: a step that raises the objective is taken again, more damped.
    bool taken = false;
    Vec6 d = Vec6::Zero();
    for (int tries = 0; tries < 10 && !taken; ++tries) {
      Mat6 A = L.H;
      A.diagonal() += lambda * L.H.diagonal().cwiseMax(1e-9);
      d = A.ldlt().solve(-L.g);
      if (!d.allFinite()) return r;
      const Eigen::Isometry3d next = step(d, r.transform);
      Linearized N = at(next, true);
      if (N.matched >= 6 && N.cost <= L.cost) {
        r.transform = next;
        L = std::move(N);
        keep(L);
        lambda = std::max(1e-9, lambda / 10);
        taken = true;
      } else {
        lambda *= 10;
      }
    }
    if (!taken || (d.tail<3>().norm() < p.translation_eps && d.head<3>().norm() < p.rotation_eps)) {
      r.converged = true;
      ++r.iterations;
      return r;
    }
  }
  return r;
}

RegistrationResult register_scan(const Points& scan, const Covariances& covs, const std::vector<const VoxelMap*>& maps,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p, const PosePrior* prior) {
  RegistrationResult r;
  r.transform = guess;
  int iterations = 0;
  for (const VoxelMap* m : maps) {
    if (!m) continue;
    r = register_scan(scan, covs, *m, r.transform, p, prior);
    iterations += r.iterations;
  }
  r.iterations = iterations;
  return r;
}

}  // namespace brickyard::mapping
