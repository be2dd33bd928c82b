#include "vgicp.hpp"

#include <algorithm>
#include <cmath>

namespace brickyard::mapping {

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

struct Linearized {
  Mat6 H = Mat6::Zero();
  Vec6 g = Vec6::Zero();
  double cost = 0;
  std::size_t matched = 0;
};

// The objective at T and its Gauss-Newton system for a step that turns the scan by omega about
// the scan's origin in the map (T's translation, o) and moves it by v:
//   T' = (exp(omega) (T - o) + o) + v,   e_i = mu_v - T a_i changes by [T a_i - o]x omega - v.
// Why about o and not the map's origin: the step's coordinates are then the car's own turn and
// motion (the system's inverse is the car's pose covariance; about the map's origin a turn
// moves the car by omega x t, kilometres away), and the lever arms are metres, so single
// precision holds: each point's arithmetic is float, in coordinates relative to o, summed into
// double every block of points.
Linearized linearize(const Points& scan, const Covariances& covs, const VoxelMap& map, const Eigen::Isometry3d& T,
                     const RegistrationParams& p) {
  Linearized out;
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3d o = T.translation();
  const Eigen::Vector3f of = o.cast<float>();
  const float s = map.voxel_size();
  const Eigen::Vector3f offsets[7] = {{0, 0, 0}, {s, 0, 0}, {-s, 0, 0}, {0, s, 0}, {0, -s, 0}, {0, 0, s}, {0, 0, -s}};
  const int looks = p.face_neighbours ? 7 : 1;
  const std::size_t stride = static_cast<std::size_t>(std::max(1, p.stride));
  const float weight = static_cast<float>(p.weight * static_cast<double>(stride));
  // The system's blocks, float within a block of points: rotation-rotation, rotation-translation,
  // translation-translation (W itself), and the gradient's halves.
  Eigen::Matrix3f Hrr = Eigen::Matrix3f::Zero(), Hrt = Eigen::Matrix3f::Zero(), Htt = Eigen::Matrix3f::Zero();
  Eigen::Vector3f gr = Eigen::Vector3f::Zero(), gt = Eigen::Vector3f::Zero();
  float cost = 0;
  auto flush = [&] {
    out.H.topLeftCorner<3, 3>() += Hrr.cast<double>();
    out.H.topRightCorner<3, 3>() += Hrt.cast<double>();
    out.H.bottomRightCorner<3, 3>() += Htt.cast<double>();
    out.g.head<3>() += gr.cast<double>();
    out.g.tail<3>() += gt.cast<double>();
    out.cost += cost;
    Hrr.setZero(), Hrt.setZero(), Htt.setZero(), gr.setZero(), gt.setZero();
    cost = 0;
  };
  const std::size_t n = std::min(scan.size(), covs.size());
  std::size_t block = 0;
  // Each point's own voxel's slot is fetched kAhead points early.
  constexpr std::size_t kAhead = 8;
  const std::size_t ahead = kAhead * stride;
  for (std::size_t i = 0; i < ahead && i < n; i += stride) map.prefetch(map.key(R * scan[i] + of));
  for (std::size_t i = 0; i < n; i += stride) {
    if (i + ahead < n) map.prefetch(map.key(R * scan[i + ahead] + of));
    const Eigen::Vector3f r = R * scan[i];  // the point relative to o, in the map's axes
    const Eigen::Vector3f q = r + of;       // in the map
    const Eigen::Matrix3f rcr = R * covs[i] * R.transpose();
    bool any = false;
    for (int k = 0; k < looks; ++k) {
      const VoxelTarget* v = map.target(map.key(q + offsets[k]));
      if (!v) continue;
      any = true;
      const Eigen::Vector3f e = (v->mean - of) - r;
      const Eigen::Matrix3f W = (weight * v->count) * (v->covariance + rcr).inverse();
      if (!W.allFinite()) continue;
      const Eigen::Vector3f We = W * e;
      cost += e.dot(We);
      // J = [ [r]x, -I ]: H = J^T W J, g = J^T W e, with [r]x^T = -[r]x.
      Eigen::Matrix3f X;
      X << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
      const Eigen::Matrix3f WX = W * X;
      Hrr.noalias() -= X * WX;
      Hrt.noalias() += X * W;
      Htt += W;
      gr.noalias() -= X * We;
      gt -= We;
    }
    out.matched += any;
    if ((++block & 255) == 0) flush();
  }
  flush();
  out.H.bottomLeftCorner<3, 3>() = out.H.topRightCorner<3, 3>().transpose();
  return out;
}

// The prior's term at T, added to L (see PosePrior): r = (log(R R_p^T), t - t_p) changes by
// (omega, v) in the step's coordinates (the turn is about T's own position).
void add_prior(const PosePrior& pr, const Eigen::Isometry3d& T, Linearized& L) {
  Vec6 r;
  const Eigen::AngleAxisd turn(T.linear() * pr.mean.linear().transpose());
  r.head<3>() = turn.angle() * turn.axis();
  r.tail<3>() = T.translation() - pr.mean.translation();
  const Vec6 Lr = pr.information * r;
  L.cost += r.dot(Lr);
  L.H += pr.information;
  L.g += Lr;
}

// The step (omega, v) from T: a turn about T's position, then a move.
Eigen::Isometry3d step(const Vec6& d, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d w = d.head<3>(), v = d.tail<3>();
  const double a = w.norm();
  const Eigen::Matrix3d dR = a > 0 ? Eigen::AngleAxisd(a, w / a).toRotationMatrix() : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = dR * T.linear();
  out.translation() = T.translation() + v;
  return out;
}

}  // namespace

RegistrationResult register_scan(const Points& scan, const Covariances& covs, const VoxelMap& map,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p, const PosePrior* prior) {
  RegistrationResult r;
  r.transform = guess;
  double lambda = 1e-6;
  auto at = [&](const Eigen::Isometry3d& T) {
    Linearized L = linearize(scan, covs, map, T, p);
    if (prior) add_prior(*prior, T, L);
    return L;
  };
  // Each trial point is linearized in full: a step that is taken needs no second pass at its
  // point (the trial's system is the next iteration's).
  Linearized L = at(r.transform);
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
      Linearized N = at(next);
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
  std::size_t last = maps.size();
  while (last > 0 && !maps[last - 1]) --last;
  for (std::size_t k = 0; k < last; ++k) {
    if (!maps[k]) continue;
    RegistrationParams stage = p;
    if (k + 1 < last) stage.stride = std::max(1, p.stride) * std::max(1, p.coarse_stride);
    r = register_scan(scan, covs, *maps[k], r.transform, stage, prior);
    iterations += r.iterations;
  }
  r.iterations = iterations;
  return r;
}

}  // namespace brickyard::mapping
