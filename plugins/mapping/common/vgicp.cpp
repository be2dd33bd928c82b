#include "vgicp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

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

// The float sums of one block of matches: the system's upper triangle (the rotation block rr,
// the cross block rt, the translation block tt = W itself, the gradient's halves) and the cost.
struct BlockSums {
  float rr00 = 0, rr01 = 0, rr02 = 0, rr11 = 0, rr12 = 0, rr22 = 0;
  float rt[3][3] = {};
  float tt00 = 0, tt01 = 0, tt02 = 0, tt11 = 0, tt12 = 0, tt22 = 0;
  float gr0 = 0, gr1 = 0, gr2 = 0, gt0 = 0, gt1 = 0, gt2 = 0, cost = 0;

  // The match of point r (relative to o, in the map's axes; its surface vector m in them too)
  // to voxel v, its terms weighted by `weight`.
  void add(const VoxelTarget& v, const Eigen::Vector3f& r, const Eigen::Vector3f& m, const Eigen::Vector3f& of, float weight) {
    const float* B = v.inverse;  // (B^-1) upper triangle: 00 01 02 11 12 22
    const float u0 = B[0] * m.x() + B[1] * m.y() + B[2] * m.z();
    const float u1 = B[1] * m.x() + B[3] * m.y() + B[4] * m.z();
    const float u2 = B[2] * m.x() + B[4] * m.y() + B[5] * m.z();
    const float den = 1.0f - (m.x() * u0 + m.y() * u1 + m.z() * u2);
    if (!(den > 0)) return;
    const float w = weight * v.count, c = w / den;
    // W = w B^-1 + c u u^T
    const float w00 = w * B[0] + c * u0 * u0, w01 = w * B[1] + c * u0 * u1, w02 = w * B[2] + c * u0 * u2;
    const float w11 = w * B[3] + c * u1 * u1, w12 = w * B[4] + c * u1 * u2, w22 = w * B[5] + c * u2 * u2;
    const float e0 = (v.mean.x() - of.x()) - r.x(), e1 = (v.mean.y() - of.y()) - r.y(), e2 = (v.mean.z() - of.z()) - r.z();
    const float we0 = w00 * e0 + w01 * e1 + w02 * e2;
    const float we1 = w01 * e0 + w11 * e1 + w12 * e2;
    const float we2 = w02 * e0 + w12 * e1 + w22 * e2;
    const float ec = e0 * we0 + e1 * we1 + e2 * we2;
    if (!std::isfinite(ec)) return;
    cost += ec;
    // J = [ [r]x, -I ]: H = J^T W J, g = J^T W e. The translation block is W; the cross
    // block [r]x W has columns r x W_j; the rotation block -[r]x W [r]x has rows r x A_i,
    // A_i the rows of [r]x W; the gradient's rotation half is -(r x We).
    const float rx = r.x(), ry = r.y(), rz = r.z();
    // A = [r]x W: column j = r x W_j.
    const float a00 = ry * w02 - rz * w01, a10 = rz * w00 - rx * w02, a20 = rx * w01 - ry * w00;
    const float a01 = ry * w12 - rz * w11, a11 = rz * w01 - rx * w12, a21 = rx * w11 - ry * w01;
    const float a02 = ry * w22 - rz * w12, a12 = rz * w02 - rx * w22, a22 = rx * w12 - ry * w02;
    rt[0][0] += a00, rt[0][1] += a01, rt[0][2] += a02;
    rt[1][0] += a10, rt[1][1] += a11, rt[1][2] += a12;
    rt[2][0] += a20, rt[2][1] += a21, rt[2][2] += a22;
    // rows of -[r]x W [r]x: r x (a_i0, a_i1, a_i2)
    rr00 += ry * a02 - rz * a01, rr01 += rz * a00 - rx * a02, rr02 += rx * a01 - ry * a00;
    rr11 += rz * a10 - rx * a12, rr12 += rx * a11 - ry * a10;
    rr22 += rx * a21 - ry * a20;
    tt00 += w00, tt01 += w01, tt02 += w02, tt11 += w11, tt12 += w12, tt22 += w22;
    gr0 -= ry * we2 - rz * we1, gr1 -= rz * we0 - rx * we2, gr2 -= rx * we1 - ry * we0;
    gt0 -= we0, gt1 -= we1, gt2 -= we2;
  }

  // The block's sums added into the double system (its upper triangle).
  void add_to(Linearized& out) const {
    Mat6& H = out.H;
    H(0, 0) += rr00, H(0, 1) += rr01, H(0, 2) += rr02, H(1, 1) += rr11, H(1, 2) += rr12, H(2, 2) += rr22;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) H(a, 3 + b) += rt[a][b];
    H(3, 3) += tt00, H(3, 4) += tt01, H(3, 5) += tt02, H(4, 4) += tt11, H(4, 5) += tt12, H(5, 5) += tt22;
    out.g(0) += gr0, out.g(1) += gr1, out.g(2) += gr2, out.g(3) += gt0, out.g(4) += gt1, out.g(5) += gt2;
    out.cost += cost;
  }
};

// A block's point matched to a voxel.
struct Match {
  const VoxelTarget* v;
  std::uint32_t point;  // in the block
};

// The scan's points at T looked up in the map, block by block: each point's voxels (its own, and
// with face_neighbours the 6 that share a face with it), the voxels' loads started as they are found.
class BlockMatcher {
 public:
  static constexpr std::size_t kBlock = 128, kAhead = 8;

  BlockMatcher(const Points& scan, const Surfaces& surfaces, const VoxelMap& map, const Eigen::Isometry3d& T, const RegistrationParams& p)
      : scan_(scan), surfaces_(surfaces), map_(map), R_(T.linear().cast<float>()), of_(T.translation().cast<float>()),
        looks_(p.face_neighbours ? 7 : 1), rs_(kBlock), ms_(kBlock), keys_(kBlock * static_cast<std::size_t>(looks_)) {
    const float vs = map.voxel_size();
    const Eigen::Vector3f offsets[7] = {{0, 0, 0}, {vs, 0, 0}, {-vs, 0, 0}, {0, vs, 0}, {0, -vs, 0}, {0, 0, vs}, {0, 0, -vs}};
    std::copy(offsets, offsets + 7, offsets_);
    matches_.reserve(kBlock * static_cast<std::size_t>(looks_));
    points_.reserve(kBlock);
  }

  const Eigen::Vector3f& origin() const { return of_; }
  const std::vector<Match>& matches() const { return matches_; }
  const Eigen::Vector3f& r(const Match& mt) const { return rs_[mt.point]; }  // the point relative to o, in the map's axes
  const Eigen::Vector3f& m(const Match& mt) const { return ms_[mt.point]; }  // its surface vector in the map's axes

  // The block of every stride-th point from b0 (kBlock of them at most) matched; returns how
  // many of its points found a voxel.
  std::size_t match(std::size_t b0, std::size_t n, std::size_t stride) {
    points_.clear();
    for (std::size_t i = b0; i < n && points_.size() < kBlock; i += stride) points_.push_back(i);
    const std::size_t np = points_.size();
    for (std::size_t j = 0; j < np; ++j) {
      rs_[j] = R_ * scan_[points_[j]];
      ms_[j] = R_ * surfaces_[points_[j]];
      const Eigen::Vector3f q = rs_[j] + of_;
      for (int k = 0; k < looks_; ++k) keys_[j * looks_ + k] = map_.key(q + offsets_[k]);
    }
    return find_voxels(np * static_cast<std::size_t>(looks_));
  }

 private:
  // The hash slots prefetched kAhead lookups early, each voxel found prefetched a whole block before it is read.
  std::size_t find_voxels(std::size_t nk) {
    std::size_t matched = 0;
    for (std::size_t a = 0; a < kAhead && a < nk; ++a) map_.prefetch(keys_[a]);
    matches_.clear();
    std::uint32_t last = ~0u;
    for (std::size_t a = 0; a < nk; ++a) {
      if (a + kAhead < nk) map_.prefetch(keys_[a + kAhead]);
      const VoxelTarget* v = map_.target(keys_[a]);
      if (!v) continue;
      __builtin_prefetch(v);
      const std::uint32_t j = static_cast<std::uint32_t>(a / static_cast<std::size_t>(looks_));
      matches_.push_back({v, j});
      matched += j != last;
      last = j;
    }
    return matched;
  }

  const Points& scan_;
  const Surfaces& surfaces_;
  const VoxelMap& map_;
  const Eigen::Matrix3f R_;
  const Eigen::Vector3f of_;
  Eigen::Vector3f offsets_[7];
  const int looks_;
  std::vector<Eigen::Vector3f> rs_, ms_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::size_t> points_;
  std::vector<Match> matches_;
};

// The objective at T and its Gauss-Newton system for a step that turns the scan by omega about
// the scan's origin in the map (T's translation, o) and moves it by v:
//   T' = (exp(omega) (T - o) + o) + v,   e_i = mu_v - T a_i changes by [T a_i - o]x omega - v.
// Why about o and not the map's origin: the step's coordinates are then the car's own turn and
// motion (the system's inverse is the car's pose covariance; about the map's origin a turn
// moves the car by omega x t, kilometres away), and the lever arms are metres, so single
// precision holds: each point's arithmetic is float, in coordinates relative to o, summed into
// double every block of points.
//
// The weight of a match, (Sigma_v + R C_i R^T)^-1 with C_i = I - s s^T (covariances.hpp) and
// m = R s, is (B - m m^T)^-1 for the voxel's B = Sigma_v + I, whose inverse the voxel holds:
// Sherman-Morrison gives B^-1 + u u^T / (1 - m^T u), u = B^-1 m. The denominator is at least
// epsilon (B >= I and |m|^2 = 1 - epsilon), so it never vanishes.
Linearized linearize(const Points& scan, const Surfaces& surfaces, const VoxelMap& map, const Eigen::Isometry3d& T,
                     const RegistrationParams& p) {
  Linearized out;
  const std::size_t stride = static_cast<std::size_t>(std::max(1, p.stride));
  const float weight = static_cast<float>(p.weight * static_cast<double>(stride));
  const std::size_t n = std::min(scan.size(), surfaces.size());
  // Block by block of points, in two passes. The first finds each point's voxels and starts
  // loading them (a scan's lookups are scattered over the map, each a cache miss). The second
  // does the arithmetic in float sums, added into double at the end of each block.
  BlockMatcher blocks(scan, surfaces, map, T, p);
  for (std::size_t b0 = 0; b0 < n; b0 += BlockMatcher::kBlock * stride) {
    out.matched += blocks.match(b0, n, stride);
    BlockSums sums;
    for (const Match& mt : blocks.matches()) sums.add(*mt.v, blocks.r(mt), blocks.m(mt), blocks.origin(), weight);
    sums.add_to(out);
  }
  // The lower triangle from the upper.
  const Mat6 upper = out.H;
  out.H = upper.selfadjointView<Eigen::Upper>();
  return out;
}

// The prior's term at T, added to L (see PosePrior): r = (log(R R_p^T), t - t_p) changes by
// (omega, v) in the step's coordinates (the turn is about T's own position).
void add_prior(const PosePrior& pr, const Eigen::Isometry3d& T, Linearized& L) {
  const Vec6 r = prior_residual(pr.mean, T);
  const Vec6 Lr = pr.information * r;
  L.cost += r.dot(Lr);
  L.H += pr.information;
  L.g += Lr;
}


}  // namespace

Eigen::Matrix<double, 6, 1> prior_residual(const Eigen::Isometry3d& mean, const Eigen::Isometry3d& T) {
  Eigen::Matrix<double, 6, 1> r;
  const Eigen::AngleAxisd turn(T.linear() * mean.linear().transpose());
  r.head<3>() = turn.angle() * turn.axis();
  r.tail<3>() = T.translation() - mean.translation();
  return r;
}

Eigen::Isometry3d moved_by(const Eigen::Matrix<double, 6, 1>& d, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d w = d.head<3>(), v = d.tail<3>();
  const double a = w.norm();
  const Eigen::Matrix3d dR = a > 0 ? Eigen::AngleAxisd(a, w / a).toRotationMatrix() : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = dR * T.linear();
  out.translation() = T.translation() + v;
  return out;
}

RegistrationResult register_scan(const Points& scan, const Surfaces& surfaces, const VoxelMap& map,
                                 const Eigen::Isometry3d& guess, const RegistrationParams& p, const PosePrior* prior) {
  RegistrationResult r;
  r.transform = guess;
  double lambda = 1e-6;
  auto at = [&](const Eigen::Isometry3d& T) {
    Linearized L = linearize(scan, surfaces, map, T, p);
    if (prior) add_prior(*prior, T, L);
    return L;
  };
  // Each trial point is linearized in full: a step that is taken needs no second pass at its
  // point (the trial's system is the next iteration's).
  Linearized L = at(r.transform);
  auto keep = [&](const Linearized& at_T) {
    r.hessian = at_T.H;
    r.gradient = at_T.g;
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
      const Eigen::Isometry3d next = moved_by(d, r.transform);
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

RegistrationResult register_scan(const Points& scan, const Surfaces& surfaces, const std::vector<const VoxelMap*>& maps,
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
    r = register_scan(scan, surfaces, *maps[k], r.transform, stage, prior);
    iterations += r.iterations;
  }
  r.iterations = iterations;
  return r;
}

}  // namespace brickyard::mapping
