// Mapping's algorithms: point covariances, the voxel map, scan-to-map registration by
// voxelized GICP. Beside PCL's GICP: test_mapping_pcl.cpp.
#include "mapping/common/covariances.hpp"
#include "mapping/common/gravity_tilt.hpp"
#include "mapping/common/mapping_run.hpp"
#include "track/track.hpp"
#include "mapping/common/pcd.hpp"
#include "mapping/common/scan_mapper.hpp"
#include "mapping/common/track_compare.hpp"
#include "mapping/common/track_extraction.hpp"
#include "track/banking.hpp"
#include "mapping/common/gicp.hpp"
#include "mapping/common/vgicp.hpp"
#include "scenes.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <array>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

using namespace brickyard::mapping;
using namespace brickyard::mapping::scenes;

namespace {

double angle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

}  // namespace

// Points on a wall: the covariance is flat across the wall (its normal the least spread).
TEST(Mapping, CovariancesAreFlatOnASurface) {
  Points wall;
  for (double x = 0; x < 4; x += 0.1)
    for (double z = 0; z < 1.2; z += 0.1) wall.emplace_back(x, 2.0, z);
  const Covariances c = point_covariances(wall);
  ASSERT_EQ(c.size(), wall.size());
  const Eigen::Vector3f normal(0, 1, 0);
  for (std::size_t i = 0; i < c.size(); i += 7) {
    EXPECT_NEAR(normal.dot(c[i] * normal), 1e-3, 1e-4) << "point " << i;
    EXPECT_NEAR(Eigen::Vector3f(1, 0, 0).dot(c[i] * Eigen::Vector3f(1, 0, 0)) + Eigen::Vector3f(0, 0, 1).dot(c[i] * Eigen::Vector3f(0, 0, 1)),
                2.0, 1e-3);
  }
  // A lone point: the identity.
  Points lone = wall;
  lone.emplace_back(50, 50, 50);
  EXPECT_TRUE(point_covariances(lone).back().isApprox(Covariance::Identity()));
}

// Each point's surface is the plane of its k nearest neighbours within the radius, found here by
// brute force (every pair, sorted, the full eigen decomposition): the grid search, its bound on
// the candidates and the normal alone (point_surfaces) give the same axis. The cloud mixes
// dense surfaces, a sparse patch (spacing 0.6 m: the bound from the point before misses, the
// radius is searched) and lone points (s = 0).
TEST(Mapping, SurfacesAreTheNearestNeighboursPlanes) {
  Points pts = yard(0.15, 0.01, 1);
  for (double x = 30; x <= 36; x += 0.6)
    for (double y = 0; y <= 6; y += 0.6) pts.emplace_back(x, y, 0.1 * y);
  pts.emplace_back(60, 60, 60);
  pts.emplace_back(60.5, 60, 60);
  CovarianceParams p;
  const Surfaces s = point_surfaces(pts, p);
  ASSERT_EQ(s.size(), pts.size());
  const float flat = std::sqrt(1.0f - p.epsilon);
  int checked = 0, lone = 0;
  for (std::size_t i = 0; i < pts.size(); i += 13) {
    std::vector<std::pair<float, std::size_t>> near;
    for (std::size_t j = 0; j < pts.size(); ++j) {
      const float d2 = (pts[j] - pts[i]).squaredNorm();
      if (d2 <= p.radius * p.radius) near.emplace_back(d2, j);
    }
    std::sort(near.begin(), near.end());
    near.resize(std::min<std::size_t>(near.size(), p.neighbours));
    if (near.size() < 3) {
      EXPECT_EQ(s[i], Eigen::Vector3f::Zero()) << "point " << i;
      ++lone;
      continue;
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& [d2, j] : near) mean += pts[j].cast<double>();
    mean /= static_cast<double>(near.size());
    Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
    for (const auto& [d2, j] : near) c += (pts[j].cast<double>() - mean) * (pts[j].cast<double>() - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
    if (es.eigenvalues()(1) < 10 * es.eigenvalues()(0)) continue;  // no clear plane: any axis is as good
    EXPECT_NEAR(s[i].norm(), flat, 1e-5) << "point " << i;
    EXPECT_NEAR(std::abs(s[i].cast<double>().dot(es.eigenvectors().col(0))), flat, 1e-3) << "point " << i;
    ++checked;
  }
  EXPECT_GT(checked, 500);
  EXPECT_GE(lone, 1);
  // The covariance the surface stands for: spread 1 along the plane, epsilon across it.
  const Covariance c = covariance_of(s[0]);
  const Eigen::Vector3f n = s[0].normalized();
  EXPECT_NEAR(n.dot(c * n), p.epsilon, 1e-5);
}

// On two threads (each half of the cells' points) the surfaces are one thread's, bit for bit: the
// sparse patch and the lone points fall in either half.
TEST(Mapping, SurfacesOnTwoThreadsAreOneThreadsBitForBit) {
  Points pts = yard(0.15, 0.01, 1);
  for (double x = 30; x <= 36; x += 0.6)
    for (double y = 0; y <= 6; y += 0.6) pts.emplace_back(x, y, 0.1 * y);
  pts.emplace_back(60, 60, 60);
  ASSERT_GT(pts.size(), 4096u);  // past the size below which one thread does it all
  const Surfaces one = point_surfaces(pts, {}, 1), two = point_surfaces(pts, {}, 2);
  ASSERT_EQ(one.size(), two.size());
  std::size_t differ = 0, zero = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    differ += one[i] != two[i];
    zero += one[i] == Eigen::Vector3f::Zero();
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_LT(zero, one.size() / 10);  // surfaces were found, not left zero on both
}

// A voxel map grown in pieces (frame by frame, as the scan mapper grows one) holds what the same
// points added at once give, voxel for voxel.
TEST(Mapping, AVoxelMapGrownInPiecesIsTheSameAsAtOnce) {
  const Points pts = yard(0.15, 0.01, 1);
  const Covariances covs = point_covariances(pts);
  VoxelMap whole(0.5f), pieces(0.5f);
  whole.add(pts, covs);
  for (std::size_t first = 0; first < pts.size(); first += 1000) {
    const std::size_t last = std::min(pts.size(), first + 1000);
    pieces.add(Points(pts.begin() + first, pts.begin() + last), Covariances(covs.begin() + first, covs.begin() + last));
  }
  ASSERT_EQ(whole.size(), pieces.size());
  ASSERT_GT(whole.size(), 100u);
  for (std::size_t v = 0; v < whole.size(); ++v) {
    const Voxel &a = whole.voxels()[v], &b = pieces.voxels()[v];
    EXPECT_EQ(a.count, b.count) << "voxel " << v;
    EXPECT_TRUE(a.mean().isApprox(b.mean(), 1e-12)) << "voxel " << v;
    const VoxelTarget* t = pieces.target(a.mean().cast<float>());
    ASSERT_NE(t, nullptr);
    EXPECT_NEAR(t->count, a.count, 0) << "voxel " << v;
  }
}

// The registration's system at its result is GICP's, summed here term by term in double with the
// voxels' own means and covariances and a 3x3 inverse per match: the closed-form weights
// (Sherman-Morrison on each voxel's stored inverse), the blocks' cross products and the float
// sums change nothing beyond rounding. For both the own voxel (DIRECT1) and the face
// neighbours (DIRECT7).
TEST(Mapping, TheRegistrationsSystemIsGicpsTermByTerm) {
  const Points map_pts = yard(0.15, 0.01, 1);
  VoxelMap map(0.5f);
  map.add(map_pts, point_covariances(map_pts));
  Eigen::Isometry3d truth(Eigen::Translation3d(0.1, -0.05, 0.02));
  truth.rotate(Eigen::AngleAxisd(1 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  const Points scan = moved(yard(0.2, 0.01, 2), truth.inverse());
  const Surfaces s = point_surfaces(scan);
  for (const bool faces : {false, true}) {
    RegistrationParams rp;
    rp.face_neighbours = faces;
    rp.max_iterations = 3;  // anywhere: the system is checked where the search stopped
    const RegistrationResult r = register_scan(scan, s, map, Eigen::Isometry3d::Identity(), rp);
    ASSERT_GT(r.matched, scan.size() / 2);
    const Eigen::Matrix3f Rf = r.transform.linear().cast<float>();
    const Eigen::Vector3f of = r.transform.translation().cast<float>();
    const Eigen::Matrix3d R = r.transform.linear();
    const double vs = map.voxel_size();
    const Eigen::Vector3d offsets[7] = {{0, 0, 0}, {vs, 0, 0}, {-vs, 0, 0}, {0, vs, 0}, {0, -vs, 0}, {0, 0, vs}, {0, 0, -vs}};
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    double cost = 0;
    for (std::size_t i = 0; i < scan.size(); ++i) {
      const Eigen::Vector3f rf = Rf * scan[i];
      const Eigen::Vector3d rel = rf.cast<double>(), q = (rf + of).cast<double>();
      for (int k = 0; k < (faces ? 7 : 1); ++k) {
        const Voxel* v = map.at(q + offsets[k]);
        if (!v) continue;
        const Eigen::Vector3d e = v->mean() - r.transform.translation() - rel;
        const Eigen::Matrix3d W = v->count * (v->covariance() + R * covariance_of(s[i]).cast<double>() * R.transpose()).inverse();
        Eigen::Matrix<double, 3, 6> J;
        J << 0, -rel.z(), rel.y(), -1, 0, 0, rel.z(), 0, -rel.x(), 0, -1, 0, -rel.y(), rel.x(), 0, 0, 0, -1;
        H += J.transpose() * W * J;
        cost += e.dot(W * e);
      }
    }
    EXPECT_LT((r.hessian - H).norm(), 1e-4 * H.norm()) << "DIRECT" << (faces ? 7 : 1) << "\n" << r.hessian << "\n\n" << H;
    EXPECT_NEAR(r.cost * static_cast<double>(r.matched), cost, 1e-3 * cost);
  }
}

// A scan of the yard (another sampling, other noise) taken from a pose 0.4 m and 3 deg off is
// brought back onto the yard's map within a centimetre and 0.05 deg, from a guess of no motion
// and from a guess near the truth (coarse to fine: 1 m voxels, then 0.25 m). The coarse map alone
// is not that accurate: more than a centimetre off.
TEST(Mapping, RegistrationFindsTheScansPose) {
  const Points map_pts = yard(0.15, 0.01, 1);
  const Covariances map_covs = point_covariances(map_pts);
  VoxelMap coarse(1.0f), fine(0.25f);
  coarse.add(map_pts, map_covs);
  fine.add(map_pts, map_covs);
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translate(Eigen::Vector3d(0.4, -0.3, 0.05));
  truth.rotate(Eigen::AngleAxisd(3 * M_PI / 180, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.5 * M_PI / 180, Eigen::Vector3d::UnitX()));
  const Points scan = moved(yard(0.2, 0.01, 2), truth.inverse());  // the scan, in its own frame
  const Surfaces surfaces = point_surfaces(scan);
  for (const Eigen::Isometry3d& guess : {Eigen::Isometry3d::Identity(), Eigen::Isometry3d(Eigen::Translation3d(0.35, -0.25, 0))}) {
    const RegistrationResult r = register_scan(scan, surfaces, {&coarse, &fine}, guess);
    EXPECT_TRUE(r.converged);
    EXPECT_LT((r.transform.translation() - truth.translation()).norm(), 0.01) << r.transform.translation().transpose();
    EXPECT_LT(angle(r.transform.linear().transpose() * truth.linear()) * 180 / M_PI, 0.05);
    EXPECT_GT(r.matched, scan.size() * 9 / 10);
  }
  const RegistrationResult alone = register_scan(scan, surfaces, coarse, Eigen::Isometry3d::Identity());
  EXPECT_GT((alone.transform.translation() - truth.translation()).norm(), 0.01);
}

// GICP with point correspondences (gicp.hpp) finds the yard's scan from two guesses, the same
// answer from both, and ends on a fixed point: registered again from its answer it stays.
// Nothing to match keeps the guess.
TEST(Mapping, PointGicpFindsTheScansPoseAndStaysThere) {
  const Points target = yard(0.15, 0.01, 1);
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translate(Eigen::Vector3d(0.4, -0.3, 0.05));
  truth.rotate(Eigen::AngleAxisd(3 * M_PI / 180, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.5 * M_PI / 180, Eigen::Vector3d::UnitX()));
  const Points scan = moved(yard(0.2, 0.01, 2), truth.inverse());
  const Surfaces ss = point_surfaces(scan), ts = point_surfaces(target);
  PointRegistrationParams p;
  p.max_correspondence_m = 1.0;
  RegistrationResult found[2];
  int k = 0;
  for (const Eigen::Isometry3d& guess : {Eigen::Isometry3d::Identity(), Eigen::Isometry3d(Eigen::Translation3d(0.35, -0.25, 0))}) {
    const RegistrationResult r = found[k++] = register_points(scan, ss, target, ts, guess, p);
    EXPECT_TRUE(r.converged);
    EXPECT_LT((r.transform.translation() - truth.translation()).norm(), 0.01) << r.transform.translation().transpose();
    EXPECT_LT(angle(r.transform.linear().transpose() * truth.linear()) * 180 / M_PI, 0.05);
    EXPECT_GT(r.matched, scan.size() * 9 / 10);
  }
  EXPECT_LT((found[0].transform.translation() - found[1].transform.translation()).norm(), 1e-4);
  const RegistrationResult again = register_points(scan, ss, target, ts, found[0].transform, p);
  EXPECT_TRUE(again.converged);
  EXPECT_LE(again.iterations, 2);
  EXPECT_LT((again.transform.translation() - found[0].transform.translation()).norm(), 1e-5);
  // Nothing within reach, non-finite points, surfaces that do not fit: the guess, not converged.
  const Eigen::Isometry3d far(Eigen::Translation3d(100, 0, 0));
  for (const RegistrationResult& r : {register_points(scan, ss, target, ts, far, p), register_points(Points{Eigen::Vector3f(NAN, 0, 0)}, Surfaces(1, Eigen::Vector3f::Zero()), target, ts, far, p),
                                      register_points(scan, Surfaces{}, target, ts, far, p)}) {
    EXPECT_FALSE(r.converged);
    EXPECT_TRUE(r.transform.isApprox(far));
  }
}

// The registration's system is over the car's own turn and position (the step turns the scan
// about its origin), so its inverse is the car's pose covariance wherever the map is: the yard
// registered 3 km from the map's origin gives the same position covariance as at the origin, and
// the same pose relative to the yard. (Turned about the map's origin, a turn moved the car by
// omega x t: the position's variance grew by t^2 sigma_omega^2.)
TEST(Mapping, ThePoseCovarianceIsTheCarsWhereverTheMapIs) {
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translate(Eigen::Vector3d(0.3, -0.2, 0.02));
  truth.rotate(Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  const Points map_here = yard(0.15, 0.01, 1);
  const Points scan = moved(yard(0.2, 0.01, 2), truth.inverse());
  const Surfaces surfaces = point_surfaces(scan);
  const Eigen::Isometry3d far(Eigen::Translation3d(3000, -2000, 40));
  RegistrationResult at[2];
  for (int k = 0; k < 2; ++k) {
    const Eigen::Isometry3d where = k ? far : Eigen::Isometry3d::Identity();
    const Points map_pts = moved(map_here, where);
    const Covariances map_covs = point_covariances(map_pts);
    VoxelMap coarse(1.0f), fine(0.25f);
    coarse.add(map_pts, map_covs);
    fine.add(map_pts, map_covs);
    at[k] = register_scan(scan, surfaces, {&coarse, &fine}, where * Eigen::Isometry3d(Eigen::Translation3d(0.25, -0.15, 0)));
    ASSERT_TRUE(at[k].converged);
    const Eigen::Isometry3d found = where.inverse() * at[k].transform;  // relative to the yard
    EXPECT_LT((found.translation() - truth.translation()).norm(), 0.01) << "k " << k;
  }
  const Eigen::Matrix3d here = planar_covariance(at[0].hessian.inverse()), there = planar_covariance(at[1].hessian.inverse());
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(there(a, a) / here(a, a), 1.0, 0.2) << "variance " << a << ": " << here(a, a) << " at the origin, "
                                                                              << there(a, a) << " 3 km away";
}

// Bad input: an empty scan or map, non-finite points: no step taken, not converged, no crash.
TEST(Mapping, RegistrationWithNothingToMatchKeepsTheGuess) {
  const Points pts = yard(0.5, 0.0, 3);
  VoxelMap empty;
  const Eigen::Isometry3d guess(Eigen::Translation3d(1, 2, 3));
  const RegistrationResult r = register_scan(pts, point_surfaces(pts), empty, guess);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.transform.isApprox(guess));
  VoxelMap map;
  map.add(pts, point_covariances(pts));
  Points bad = {Eigen::Vector3f(NAN, 0, 0), Eigen::Vector3f(INFINITY, 1, 1)};
  const RegistrationResult b = register_scan(bad, point_surfaces(bad), map, guess);
  EXPECT_FALSE(b.converged);
  EXPECT_TRUE(b.transform.isApprox(guess));
}

// In a corridor the registration fixes the pose across and in heading and leaves it where the
// prior says along the corridor, and the covariance says which is which. In the yard (boxes
// fix every direction) it fixes all three.
TEST(ScanMapper, FixesWhatTheScanShowsAndKeepsThePriorAlongACorridor) {
  const Eigen::Matrix3d prior = Eigen::Vector3d(0.5 * 0.5, 0.5 * 0.5, 0.05 * 0.05).asDiagonal();
  for (bool boxes : {false, true}) {
    ScanMapper mapper;
    const Points world = boxes ? yard(0.15, 0.01, 1) : corridor(0.15, 1);
    const ScanResult first = mapper.add(world, Eigen::Isometry3d::Identity(), planar_information(prior));
    EXPECT_TRUE(first.keyframe);
    EXPECT_FALSE(first.registered);  // nothing to register on yet
    const Eigen::Isometry3d truth = planar(2.0, 0.0, 0.0);
    const Points scan = moved(boxes ? yard(0.2, 0.01, 2) : corridor(0.2, 2), truth.inverse());
    const Eigen::Isometry3d guess = planar(2.3, 0.25, 1.0);
    const ScanResult r = mapper.add(scan, guess, planar_information(prior));
    ASSERT_TRUE(r.registered) << (boxes ? "yard" : "corridor");
    EXPECT_NEAR(r.pose.translation().y(), 0.0, 0.02) << (boxes ? "yard" : "corridor");
    EXPECT_NEAR(yaw_of(r.pose) * 180 / M_PI, 0.0, 0.05) << (boxes ? "yard" : "corridor");
    const Eigen::Matrix3d c = planar_covariance(r.covariance);
    if (boxes) {
      EXPECT_NEAR(r.pose.translation().x(), 2.0, 0.02);
      EXPECT_LT(c(0, 0), 0.01 * 0.25) << "the boxes tell along x: far below the prior's variance";
    } else {
      EXPECT_NEAR(r.pose.translation().x(), 2.3, 0.05) << "along the corridor: the prior's";
      EXPECT_GT(c(0, 0), 100 * c(1, 1)) << "the covariance says the along-track is the prior's";
      EXPECT_GT(c(0, 0), 0.5 * 0.25);
    }
  }
}

// Walls the map holds leaning (6 deg) where the frame sees them upright, as two walls' maps do
// where their sampling misleads the registration: the whole frame's registration tilts the car
// to meet them. With the frame's ground given, its roll, pitch and height come from the ground
// alone (level), and the frame joins the map on the estimate's (x, y), the registration's heading
// and the ground's roll, pitch and height.
TEST(ScanMapper, TheGroundLevelsTheFrameWhereAWallWouldTiltIt) {
  const Eigen::Matrix3d prior = Eigen::Vector3d(0.5 * 0.5, 0.5 * 0.5, 0.05 * 0.05).asDiagonal();
  const double lean = std::tan(6.0 * M_PI / 180);
  auto scene = [&](double step, unsigned seed, double wall_lean, Points* ground) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.0f, 0.01f);
    Points pts;
    for (double x = -30; x <= 30; x += step) {
      for (double y = -3; y <= 3; y += step) {
        pts.emplace_back(x + n(rng), y + n(rng), n(rng));
        if (ground) ground->push_back(pts.back());
      }
      for (double z = 0.2; z <= 3.0; z += step)
        pts.emplace_back(x + n(rng), 6 + z * wall_lean + n(rng), z), pts.emplace_back(x + n(rng), -6 + z * wall_lean + n(rng), z);
    }
    return pts;
  };
  const Eigen::Isometry3d truth = planar(2.0, 0.0, 0.0), guess = planar(2.1, 0.05, 0.2);
  double roll_whole = 0;
  for (bool level : {false, true}) {
    ScanMapper mapper;
    mapper.add(scene(0.15, 1, lean, nullptr), Eigen::Isometry3d::Identity(), planar_information(prior));
    Points ground;
    const Points scan = moved(scene(0.2, 2, 0.0, &ground), truth.inverse());
    const Points ground_v = moved(ground, truth.inverse());
    const ScanResult r = mapper.add(scan, guess, planar_information(prior), level ? &ground_v : nullptr);
    ASSERT_TRUE(r.registered) << level;
    const double roll = roll_of(r.map_pose) * 180 / M_PI, pitch = pitch_of(r.map_pose) * 180 / M_PI;
    if (!level) {
      roll_whole = roll;
      EXPECT_EQ(r.map_pose.matrix(), r.pose.matrix()) << "without the ground, the frame joins on the pose found";
      continue;
    }
    EXPECT_NEAR(roll, 0.0, 0.05);
    EXPECT_NEAR(pitch, 0.0, 0.05);
    EXPECT_NEAR(r.map_pose.translation().z(), 0.0, 0.01);
    EXPECT_NEAR(r.map_pose.translation().x(), guess.translation().x(), 1e-6) << "the estimate's (x, y)";
    EXPECT_NEAR(r.map_pose.translation().y(), guess.translation().y(), 1e-6);
    EXPECT_NEAR(yaw_of(r.map_pose), yaw_of(r.pose), 1e-9) << "the registration's heading";
    EXPECT_NEAR(yaw_of(r.map_pose) * 180 / M_PI, 0.0, 0.05) << "the walls tell the heading (the guess's was 0.2 deg off)";
  }
  EXPECT_GT(std::abs(roll_whole), 0.2) << "the leaning walls tilt the whole frame's registration (the test's premise)";
}

// Gravity finds the drift of the map's attitude: a car turning and speeding up on a road whose
// bank ramps from 0 to 9 deg in 3 s, its sideslip's rate swinging by 2 m/s^2 at 20 Hz (degrees of
// roll sample to sample), pitched 1 deg; the frames' attitude 0.5 deg off in roll and 0.3 deg in
// pitch. The drift comes out within 0.03 deg once a whole window is in, and not before; nor
// while the car is slow (the start, its speed still settling).
TEST(GravityTilt, FindsTheAttitudesDriftWhereTheBankRampsAndTheSideslipSwings) {
  const double deg = M_PI / 180, pitch = 1.0 * deg;
  auto bank = [&](double t) { return std::clamp(t - 5.0, 0.0, 3.0) / 3.0 * 9.0 * deg; };
  auto speed = [](double t) { return 30.0 + 2.0 * std::sin(0.5 * t); };
  for (double slow : {0.0, 1.0}) {
    GravityTilt g(4.0);
    Tilt d;
    bool before_window = false;
    for (int k = 0; k <= 125 * 9; ++k) {  // the last window (5 to 9 s) holds the ramp
      const double t = k / 125.0, v = speed(t) * (slow ? 0.1 : 1.0), w = 0.2;
      const double dv = 1.0 * std::cos(0.5 * t) * (slow ? 0.1 : 1.0), sideslip_rate = 2.0 * std::sin(2 * M_PI * 20 * t);
      const double f_y = v * w + sideslip_rate + kGravity * std::sin(bank(t)) * std::cos(pitch);
      const double f_x = dv - kGravity * std::sin(pitch);
      const auto ns = static_cast<std::int64_t>(k) * 8'000'000;
      g.add_imu(ns, f_x, f_y, w, v);
      if (k % 6 == 0) {  // frames at about 20 Hz
        g.add_frame(ns, bank(t) + 0.5 * deg, pitch + 0.3 * deg);
        if (t < 3.9) before_window = before_window || g.drift(d);
      }
    }
    EXPECT_FALSE(before_window) << "a drift before a whole window was in";
    if (slow) {
      EXPECT_FALSE(g.drift(d)) << "slower than min_speed";
      continue;
    }
    ASSERT_TRUE(g.drift(d));
    EXPECT_NEAR(d.roll / deg, 0.5, 0.03);
    EXPECT_NEAR(d.pitch / deg, 0.3, 0.03);
    // Turned out a part at a time: the first call none, then 50 ms of a 5 s level, 1 %.
    Tilt part;
    const std::int64_t end = std::int64_t{125 * 9} * 8'000'000;
    EXPECT_FALSE(g.correction(end, 5.0, part));
    ASSERT_TRUE(g.correction(end + 50'000'000, 5.0, part));
    EXPECT_NEAR(part.roll, 0.01 * d.roll, 1e-12);
    EXPECT_NEAR(part.pitch, 0.01 * d.pitch, 1e-12);
  }
}

// The comparison of a mapped file with the true one says how far and where: one point's left
// edge 1 m out and another's bank 2 deg off on a ring, found at their arc lengths; the same file
// the other way round is found reversed, the same error on the swapped side.
TEST(TrackCompare, SaysHowFarAndWhere) {
  brickyard::track::CenterLine truth;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    truth.x.push_back(100 * std::cos(a));
    truth.y.push_back(100 * std::sin(a));
    truth.width_left.push_back(5);
    truth.width_right.push_back(6);
  }
  brickyard::track::CenterLine mapped = truth;
  mapped.bank_deg.assign(n, 0.0);
  mapped.width_left[50] += 1.0;
  mapped.bank_deg[120] = 2.0;
  const double step = 2 * 100 * std::sin(M_PI / n);  // a chord
  const TrackComparison c = compare_tracks(mapped, truth, std::vector<double>(n, 0.0));
  EXPECT_FALSE(c.reversed);
  EXPECT_NEAR(c.edges.max, 1.0, 0.01);
  EXPECT_NEAR(c.edges_max_at_s, 50 * step, 0.5);
  EXPECT_NEAR(c.bank.max, 2.0, 1e-9);
  EXPECT_NEAR(c.bank_max_at_s, 120 * step, 0.5);
  EXPECT_NEAR(c.right.max, 0.0, 1e-6);
  brickyard::track::CenterLine back;
  for (int i = n - 1; i >= 0; --i) {
    back.x.push_back(mapped.x[i]), back.y.push_back(mapped.y[i]);
    back.width_left.push_back(mapped.width_right[i]), back.width_right.push_back(mapped.width_left[i]);
  }
  const TrackComparison r = compare_tracks(back, truth, std::vector<double>(n, 0.0));
  EXPECT_TRUE(r.reversed);
  EXPECT_NEAR(r.edges.max, 1.0, 0.01);
  EXPECT_NEAR(r.edges_max_at_s, 50 * step, 0.5);
}

// A frame joins the map only when the car has moved keyframe_distance; a registration that would
// move the estimate more than max_correction is not taken.
TEST(ScanMapper, KeyframesByDistanceAndImplausibleCorrectionsRefused) {
  ScanMapperParams p;
  p.keyframe_distance = 2.0;
  p.max_correction = 0.2;
  ScanMapper mapper(p);
  const Eigen::Matrix3d prior = Eigen::Vector3d(1, 1, 0.01).asDiagonal();
  const Points world = yard(0.15, 0.01, 1);
  mapper.add(world, Eigen::Isometry3d::Identity(), planar_information(prior));
  const std::size_t voxels = mapper.fine_map().size();
  const ScanResult still = mapper.add(yard(0.2, 0.01, 3), planar(0.0, 0.02, 0), planar_information(prior));
  EXPECT_TRUE(still.registered);
  EXPECT_FALSE(still.keyframe);
  EXPECT_EQ(mapper.fine_map().size(), voxels);
  EXPECT_EQ(mapper.keyframes(), 1u);
  // The car 0.5 m from where the estimate says: the registration finds it, but the correction is
  // more than 0.2 m, so the estimate stands.
  const ScanResult far = mapper.add(moved(yard(0.2, 0.01, 4), planar(0.5, 0, 0).inverse()), planar(0.0, 0.0, 0),
                                    planar_information(prior));
  EXPECT_FALSE(far.registered);
  EXPECT_NEAR(far.pose.translation().x(), 0.0, 1e-12);
}

// The map written as PCD is read back point for point; an unwritable place is an error naming
// the file, and no half-written file is left.
TEST(ScanMapper, MapAsPcdRoundTrip) {
  VoxelMap m(0.5f);
  const Points pts = yard(0.3, 0.0, 1);
  m.add(pts, point_covariances(pts));
  const std::string path = testing::TempDir() + "map_round_trip.pcd";
  write_pcd(path, m);
  const Points back = read_pcd(path);
  ASSERT_EQ(back.size(), m.size());
  for (std::size_t i = 0; i < back.size(); i += 17) EXPECT_TRUE(back[i].isApprox(m.voxels()[i].mean().cast<float>(), 1e-6f));
  std::remove(path.c_str());
  try {
    write_pcd("/nonexistent_dir/map.pcd", m);
    FAIL() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/map.pcd"), std::string::npos) << e.what();
  }
  std::ofstream(testing::TempDir() + "bad.pcd") << "VERSION 0.7\nFIELDS x y z\nPOINTS 3\nDATA ascii\n1 2 3\n4 5\n";
  EXPECT_THROW(read_pcd(testing::TempDir() + "bad.pcd"), std::runtime_error);
  // A FIFO where the map should be: refused unread (its read would wait for a writer for ever).
  const std::string fifo = testing::TempDir() + "/brickyard_map.fifo";
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  try {
    read_pcd(fifo);
    ADD_FAILURE() << "a FIFO read as a map";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), fifo + ": not a regular file");
  }
  std::remove(fifo.c_str());
}

// ---- the track's lines from a drive (road_surface.hpp, track_extraction.hpp) ----

namespace {

// A ring road of radius 100 m (centre line), 6 m to the left edge (inside) and 5 m to the right,
// banked 4° raising the left edge, grass beyond both edges level at the edge's height. The car
// drives 1 m left of the centre line; at every pose a sensor 1.5 m up sees the ground on a polar
// grid out to 20 m, each return's intensity its surface's reflectivity times the cosine of the ray
// against the road's normal (drop / range in the sensor's frame, which tilts with the road).
struct Ring {
  double r = 100, wl = 6, wr = 5, bank_deg = 4;
  double height(double d) const {  // d: left of the centre line
    return std::tan(bank_deg * M_PI / 180) * std::clamp(d, -wr, wl);
  }
};

// stray_every > 0: every that many poses, one return more, from the road 15 m ahead and 2 m left
// of the car, read 1.4 m high (a frame whose attitude is a few degrees off).
RoadSurface drive_ring(const Ring& ring, std::vector<Eigen::Vector2d>& driven, double laps, int stray_every = 0) {
  RoadSurface surface;
  const Eigen::Isometry3d mount(Eigen::Translation3d(0, 0, 1.5));
  const double path_r = ring.r - 1.0;  // counter-clockwise: left is inward
  for (double s = 0; s <= laps * 2 * M_PI * path_r; s += 2.0) {
    const double a = s / path_r;
    const Eigen::Vector2d at(path_r * std::cos(a), path_r * std::sin(a));
    driven.push_back(at);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(at.x(), at.y(), ring.height(1.0)));
    pose.rotate(Eigen::AngleAxisd(a + M_PI / 2, Eigen::Vector3d::UnitZ()));
    pose.rotate(Eigen::AngleAxisd(ring.bank_deg * M_PI / 180, Eigen::Vector3d::UnitX()));  // the car tilts with the road
    std::vector<float> x, y, z, in;
    for (double rho = 2; rho <= 20; rho += 0.13)
      for (double phi = 0; phi < 2 * M_PI; phi += 0.02) {
        const Eigen::Vector3d pv = pose * Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), 0);
        const double d = ring.r - std::hypot(pv.x(), pv.y());  // left of the centre line
        const Eigen::Vector3d ground(pv.x(), pv.y(), ring.height(d));
        const Eigen::Vector3d ps = (pose * mount).inverse() * ground;
        const double refl = d <= ring.wl && d >= -ring.wr ? 0.15 : 0.45;
        x.push_back(ps.x()); y.push_back(ps.y()); z.push_back(ps.z());
        in.push_back(static_cast<float>(refl * -ps.z() / ps.norm()));
      }
    if (stray_every > 0 && driven.size() % static_cast<std::size_t>(stray_every) == 0) {
      const Eigen::Vector3d stray = mount.inverse() * Eigen::Vector3d(15, 2, 1.4);
      x.push_back(static_cast<float>(stray.x())), y.push_back(static_cast<float>(stray.y())), z.push_back(static_cast<float>(stray.z()));
      in.push_back(0.1f);
    }
    surface.add_scan(x.data(), y.data(), z.data(), in.data(), x.size(), mount, pose);
  }
  return surface;
}

}  // namespace

TEST(TrackExtraction, FindsTheEdgesAndTheBankOfARingRoad) {
  const Ring ring;
  std::vector<Eigen::Vector2d> driven;
  const RoadSurface surface = drive_ring(ring, driven, 1.1);
  const ExtractedTrack t = extract_track(surface, driven);
  ASSERT_GT(t.stations, 250u);
  EXPECT_GE(t.sides_found, 2 * t.stations - 4);
  double worst_edge = 0, worst_bank = 0;
  for (std::size_t k = 0; k < t.line.x.size(); ++k) {
    const double rc = std::hypot(t.line.x[k], t.line.y[k]);
    // The left (inner) edge at r − 6, the right at r + 5, whatever the centre found.
    worst_edge = std::max({worst_edge, std::abs(rc - t.line.width_left[k] - (ring.r - ring.wl)),
                           std::abs(rc + t.line.width_right[k] - (ring.r + ring.wr))});
    worst_bank = std::max(worst_bank, std::abs(t.line.bank_deg[k] - ring.bank_deg));
  }
  EXPECT_LT(worst_edge, 0.05);
  EXPECT_LT(worst_bank, 0.2);
}

// A stray return among the road's: a frame posed a few degrees off reads the road ahead as rising
// above it (IMS's mapped inner edge 2.2 m inside the road, where turn 2's bank runs out). One such
// return in a cell of a hundred road returns is not a wall: the edges stay where they are.
TEST(TrackExtraction, AFewStrayReturnsOnTheRoadAreNotAWall) {
  const Ring ring;
  std::vector<Eigen::Vector2d> driven;
  const RoadSurface surface = drive_ring(ring, driven, 1.1, 3);
  const ExtractedTrack t = extract_track(surface, driven);
  double worst_edge = 0;
  for (std::size_t k = 0; k < t.line.x.size(); ++k) {
    const double rc = std::hypot(t.line.x[k], t.line.y[k]);
    worst_edge = std::max({worst_edge, std::abs(rc - t.line.width_left[k] - (ring.r - ring.wl)),
                           std::abs(rc + t.line.width_right[k] - (ring.r + ring.wr))});
  }
  EXPECT_LT(worst_edge, 0.05);
}

// The banking from each station's first pass: a lap on, where the loop closes onto the drive's
// first map, the registered roll tilts to reconcile the map's two ends (IMS: 0.4 deg for 250 m,
// 1.2 deg where the bank begins). Here the second lap's rolls are 1.2 deg off over a quarter of
// the ring: the file keeps the first pass's (before: the median of the two passes, 1.2 deg off).
TEST(TrackExtraction, TheBankingIsEachStationsFirstPass) {
  const Ring ring;
  std::vector<Eigen::Vector2d> driven;
  const RoadSurface surface = drive_ring(ring, driven, 2.1);
  const double lap = 2 * M_PI * (ring.r - 1.0);
  std::vector<double> roll;
  for (std::size_t i = 0; i < driven.size(); ++i) {
    const double s = 2.0 * static_cast<double>(i), a = std::fmod(s / (ring.r - 1.0), 2 * M_PI);
    const bool tilted = s > lap && a < M_PI / 2;
    roll.push_back((ring.bank_deg + (tilted ? 1.2 : 0.0)) * M_PI / 180);
  }
  const ExtractedTrack t = extract_track(surface, driven, {}, &roll);
  ASSERT_GT(t.line.bank_deg.size(), 50u);
  double worst = 0;
  for (double b : t.line.bank_deg) worst = std::max(worst, std::abs(b - ring.bank_deg));
  EXPECT_LT(worst, 0.05);
}

// A tight bend written every 6 m: a reader joins the points straight (track::Track), and on the
// bend's inside that chord cuts beyond the edge (on a 19 m radius by 0.24 m). The written widths
// are narrowed there, so the file claims no road the drive did not see, and stay 6 m apart.
// Swept over rings of 25, 15 and 11 m (inner edges 19, 10 and 6 m: a hairpin's).
TEST(TrackExtraction, TheFileClaimsNoRoadBeyondTheEdgesInATightBend) {
  for (const auto& [r, wl, wr] : {std::array<double, 3>{25, 6, 5}, {15, 5, 5}, {11, 5, 5}}) {
    Ring ring;
    ring.r = r, ring.wl = wl, ring.wr = wr;
    std::vector<Eigen::Vector2d> driven;
    const RoadSurface surface = drive_ring(ring, driven, 200.0 / (2 * M_PI * ring.r) + 1.3);
    TrackExtractionParams p;
    p.lap_from = 30;
    p.min_lap = 60;
    const ExtractedTrack t = extract_track(surface, driven, p);
    const std::size_t n = t.line.x.size();
    ASSERT_GT(n, 10u) << "ring " << r;
    EXPECT_NEAR(std::hypot(t.line.x[1] - t.line.x[0], t.line.y[1] - t.line.y[0]), 6.0, 0.7) << "ring " << r;  // three 2 m stations
    const brickyard::track::Track reader(brickyard::track::TrackGeometry{"ring", t.line, {}});
    double beyond = -1e9, inside = 1e9;  // how far the file's edges reach past the true ones, m
    for (double a = 0; a < 2 * M_PI; a += 0.002) {
      const Eigen::Vector2d dir(std::cos(a), std::sin(a));
      const Eigen::Vector2d inner = (ring.r - ring.wl) * dir, outer = (ring.r + ring.wr) * dir;
      const brickyard::track::Frenet fi = reader.project(inner.x(), inner.y()), fo = reader.project(outer.x(), outer.y());
      const double over_inner = reader.width_left(fi.seg, fi.u) - fi.d, over_outer = reader.width_right(fo.seg, fo.u) + fo.d;
      beyond = std::max(beyond, over_inner);
      inside = std::min({inside, over_inner, over_outer});
      // (Outside a bend, past a segment's end, the reader extrapolates the segment's edge, which
      // bulges outward at every vertex of any polyline file, the true ones too: not judged there.)
      if (fo.u >= 0 && fo.u <= 1) beyond = std::max(beyond, over_outer);
    }
    // Without the narrowing: 0.21, 0.37 and 0.55 m; with it 0.03, 0.05 and 0.07 m.
    EXPECT_LT(beyond, 0.08) << "ring " << r;
    // And no narrower than the chord's sagitta on the inner edge (6² / 8 R_inner) asks.
    EXPECT_GT(inside, -(36.0 / (8 * (ring.r - ring.wl)) + 0.1)) << "ring " << r;
  }
}

namespace {

// extract_track refuses the drive of `laps` round `ring`, saying `why`.
void expect_refused(const Ring& ring, double laps, const std::string& why) {
  std::vector<Eigen::Vector2d> driven;
  const RoadSurface surface = drive_ring(ring, driven, laps);
  try {
    extract_track(surface, driven);
    ADD_FAILURE() << "extracted a track; expected: " << why;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(TrackExtraction, ADriveThatNeverClosesALapIsRefused) { expect_refused(Ring{}, 0.6, "never came back"); }

// A map whose boundary cannot be closed: asphalt as far as the LiDAR sees on every side, no
// edge anywhere round the lap. Refused with the reason, no track made.
TEST(TrackExtraction, ARoadWithNoEdgeAnywhereIsRefused) {
  Ring ring;
  ring.wl = ring.wr = 1000;  // road everywhere
  expect_refused(ring, 1.1, "no edge found on one side anywhere round the lap");
}

// The mapped track's file: today's four columns and the bank angle; read back as written, its
// banking used by bank_mode "file", and a row that drops the column refused by its line.
TEST(TrackExtraction, TheTrackFileCarriesItsBanking) {
  const Ring ring;
  std::vector<Eigen::Vector2d> driven;
  const ExtractedTrack t = extract_track(drive_ring(ring, driven, 1.1), driven);
  const std::string path = ::testing::TempDir() + "mapped_track.csv";
  brickyard::track::write_centerline_csv(path, t.line);
  const brickyard::track::CenterLine back = brickyard::track::load_centerline_csv(path);
  ASSERT_EQ(back.x.size(), t.line.x.size());
  ASSERT_EQ(back.bank_deg.size(), t.line.x.size());
  for (std::size_t k = 0; k < back.x.size(); k += 37) {
    EXPECT_NEAR(back.x[k], t.line.x[k], 1e-4);
    EXPECT_NEAR(back.width_left[k], t.line.width_left[k], 1e-4);
    EXPECT_NEAR(back.bank_deg[k], t.line.bank_deg[k], 1e-3);
  }
  brickyard::track::BankSpec file;
  file.mode = "file";
  const std::vector<double> bank = brickyard::track::bank_profile(back, file);
  EXPECT_NEAR(bank[10], back.bank_deg[10] * M_PI / 180, 1e-12);
  std::istringstream mixed("# x_m,y_m,w_tr_right_m,w_tr_left_m,bank_deg\n0,0,7,7,1\n0,-5,7,7,1\n0,-10,7,7\n0,-15,7,7,1\n");
  try {
    brickyard::track::parse_centerline_csv(mixed, "mixed.csv");
    FAIL() << "a row without the bank column was read";
  } catch (const brickyard::track::TrackFileError& e) {
    EXPECT_NE(std::string(e.what()).find("mixed.csv:4"), std::string::npos) << e.what();
  }
  brickyard::track::CenterLine flat = back;
  flat.bank_deg.clear();
  EXPECT_THROW(brickyard::track::bank_profile(flat, file), std::invalid_argument);
  std::remove(path.c_str());
}

// ---- mapping.scan_mapper's run (common/mapping_run.hpp) ----

// A file the node is to write at the end: a place that cannot take it is said before the drive,
// and the probe leaves nothing behind.
TEST(MappingRun, AnUnwritablePlaceIsSaidNow) {
  EXPECT_EQ(unwritable("map_file", ""), "");
  const std::string path = testing::TempDir() + "probe_map.pcd";
  EXPECT_EQ(unwritable("map_file", path), "");
  EXPECT_FALSE(std::ifstream(path + ".part").good());
  EXPECT_EQ(unwritable("track_file", "/nonexistent_dir/track.csv"),
            "track_file '/nonexistent_dir/track.csv': cannot write there (does its folder exist?)");
}

// Each frame is registered from the estimate at its stamp (interpolated, the nearer's status and
// speed); frames with no estimate near their stamp are counted and left out; the summary's
// numbers come in the order they are reported; the files say what became of them.
TEST(MappingRun, FramesFromTheEstimateAtTheirStampAndTheSummary) {
  MappingRunParams p;
  p.level_on_ground = false;
  MappingRun run(p, true);
  const Points world = yard(0.15, 0.01, 1);
  EXPECT_FALSE(run.frame(0, world, 0, false).has_value());  // no estimate yet
  const std::array<double, 9> cov{0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.0025};
  run.estimate(0, {0, 0, 0}, {10, 0.1, cov, 0});
  run.estimate(8'000'000, {0.08, 0, 0}, {12, 0.1, cov, 1});
  EXPECT_FALSE(run.frame(200'000'000, world, 0, false).has_value());  // the nearest 192 ms off
  const std::optional<FramePose> first = run.frame(2'000'000, world, 0, false);  // starts the map
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->stamp_ns, 2'000'000);
  EXPECT_EQ(first->update_case, 0);  // nothing to register on yet: the guess
  EXPECT_NEAR(first->x, 0.02, 1e-12);
  EXPECT_EQ(first->status, 0);  // the nearer estimate's
  EXPECT_EQ(first->speed, 10);
  // The car 2 m on, the estimate 0.4 m and a degree off: the yard's walls and boxes fix it.
  run.estimate(1'000'000'000, {2.3, 0.25, M_PI / 180}, {10, 0, cov, 0});
  const std::optional<FramePose> second = run.frame(1'000'000'000, moved(yard(0.2, 0.01, 2), planar(2.0, 0.0, 0.0).inverse()), 0, false);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->update_case, 2);
  EXPECT_NEAR(second->x, 2.0 + first->x, 0.02);  // the map started on the first frame's estimate
  EXPECT_NEAR(second->y, 0.0, 0.02);
  EXPECT_NEAR(second->yaw, 0.0, 0.001);
  EXPECT_LT(second->covariance[0], 0.25);  // below the prior's
  EXPECT_TRUE(run.malformed());   // the first unreadable cloud is said...
  EXPECT_FALSE(run.malformed());  // ...once
  // A standing return 5 m ahead (sensor on the car's origin) joins the road surface.
  const float x = 5, y = 0, z = 1, intensity = 1;
  run.add_scan(&x, &y, &z, &intensity, 1, Eigen::Isometry3d::Identity(), second->map_pose);
  const auto m = run.metrics();
  ASSERT_EQ(m.size(), 10u);
  EXPECT_EQ(m[0], (std::pair<std::string, double>("frames", 2)));
  EXPECT_EQ(m[1], (std::pair<std::string, double>("registered", 1)));
  EXPECT_EQ(m[2].first, "keyframes");
  EXPECT_EQ(m[3].first, "map_voxels");
  EXPECT_EQ(m[4], (std::pair<std::string, double>("frames_without_estimate", 2)));
  EXPECT_EQ(m[5], (std::pair<std::string, double>("malformed_clouds", 2)));
  EXPECT_EQ(m[6], (std::pair<std::string, double>("correction_mean_m", std::hypot(second->x - 2.3, second->y - 0.25))));
  EXPECT_EQ(m[7].first, "correction_max_m");
  EXPECT_EQ(m[8], (std::pair<std::string, double>("road_cells", 1)));
  EXPECT_EQ(m[9], (std::pair<std::string, double>("gravity_levelled_frames", 0)));
  const std::string map_path = testing::TempDir() + "run_map.pcd";
  const FileWritten map = run.write_map(map_path);
  EXPECT_TRUE(map.ok);
  EXPECT_EQ(map.message, "map written: " + map_path + " (" + std::to_string(read_pcd(map_path).size()) + " points)");
  std::remove(map_path.c_str());
  const FileWritten nowhere = run.write_map("/nonexistent_dir/map.pcd");
  EXPECT_FALSE(nowhere.ok);
  EXPECT_NE(nowhere.message.find("/nonexistent_dir/map.pcd"), std::string::npos) << nowhere.message;
  // Two frames 2 m apart are no lap: no track, and the run says why.
  const std::string track_path = testing::TempDir() + "run_track.csv";
  const TrackWritten track = run.write_track(track_path);
  EXPECT_FALSE(track.ok);
  EXPECT_NE(track.error.find("never came back"), std::string::npos) << track.error;
  EXPECT_EQ(track.message, "track_file '" + track_path + "' not written: " + track.error);
}

TEST(MappingRun, WithoutTheRoadSurfaceRawReturnsAreLeftOut) {
  MappingRun run(MappingRunParams{}, false);
  const float x = 5, y = 0, z = 1, intensity = 1;
  run.add_scan(&x, &y, &z, &intensity, 1, Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(run.metrics()[8], (std::pair<std::string, double>("road_cells", 0)));
  EXPECT_EQ(run.write_track(testing::TempDir() + "no_track.csv").error.find("the drive never came back"), 0u);
}
