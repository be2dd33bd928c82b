// Our registration beside PCL's GICP on real scans (data/lidar, MIT, see data/lidar/LICENSE.cupcl).
#include "mapping/common/covariances.hpp"
#include "mapping/common/gicp.hpp"
#include "mapping/common/pcd.hpp"
#include "mapping/common/vgicp.hpp"
#include "pcl_baseline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <utility>

using namespace brickyard::mapping;

namespace {

std::string lidar(const char* name) { return std::string(BRICKYARD_SOURCE_DIR) + "/data/lidar/" + name; }

double apart_m(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) { return (a.block<3, 1>(0, 3) - b.block<3, 1>(0, 3)).norm(); }
double apart_deg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.block<3, 3>(0, 0).transpose() * b.block<3, 3>(0, 0))).angle() * 180 / M_PI;
}

// cuICP's pair as shipped: P, and Q without its repeats (Q holds 1,596 distinct points among its
// 7,000; a repeated point's neighbours are itself).
std::pair<Points, Points> shipped_pair() {
  const Points P = brickyard::baseline::load_pcd(lidar("cupcl_icp_P.pcd")), Qraw = brickyard::baseline::load_pcd(lidar("cupcl_icp_Q.pcd"));
  Points Q;
  for (const auto& q : Qraw)
    if (std::find(Q.begin(), Q.end(), q) == Q.end()) Q.push_back(q);
  return {P, Q};
}

// PCL's covariances: the 20 nearest, however far (a radius past the clouds' 140 m).
CovarianceParams pcl_covariances() {
  CovarianceParams cp;
  cp.neighbours = 20;
  cp.radius = 500;
  return cp;
}

// Ours, coarse to fine (1 m voxels, then 0.25 m), 20 neighbours per covariance as PCL.
Eigen::Matrix4d ours(const Points& source, const Points& target, bool must_converge = true) {
  CovarianceParams cp;
  cp.neighbours = 20;
  const Covariances tc = point_covariances(target, cp);
  VoxelMap coarse(1.0f), fine(0.25f);
  coarse.add(target, tc);
  fine.add(target, tc);
  const RegistrationResult r = register_scan(source, point_surfaces(source, cp), {&coarse, &fine}, Eigen::Isometry3d::Identity());
  if (must_converge) {
    EXPECT_TRUE(r.converged);
  }
  return r.transform.matrix();
}

}  // namespace

// A real scan (cuICP's P, 7,000 points of an outdoor scene 140 m across) and every other point of
// it moved by a known transform (0.3 m, 2 deg): ours (the voxelized registration, and GICP with
// point matches) and PCL's GICP all find it within 1 cm and 0.1 deg, and so agree with each other
// within that.
TEST(MappingPcl, RealScanWithAKnownMotionMatchesPclsGicp) {
  const Points P = brickyard::baseline::load_pcd(lidar("cupcl_icp_P.pcd"));
  ASSERT_GT(P.size(), 1000u);
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translate(Eigen::Vector3d(0.3, -0.2, 0.05));
  truth.rotate(Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  Points scan;
  for (std::size_t i = 0; i < P.size(); i += 2) scan.push_back((truth.inverse() * P[i].cast<double>()).cast<float>());
  const auto theirs = brickyard::baseline::gicp(scan, P, Eigen::Matrix4d::Identity());
  ASSERT_TRUE(theirs.converged);
  const Eigen::Matrix4d mine = ours(scan, P), T = truth.matrix();
  std::printf("known motion: PCL GICP %.4f m, %.4f deg from the truth (%.0f ms); ours %.4f m, %.4f deg; apart %.4f m, %.4f deg\n",
              apart_m(theirs.transform, T), apart_deg(theirs.transform, T), theirs.ms, apart_m(mine, T), apart_deg(mine, T),
              apart_m(mine, theirs.transform), apart_deg(mine, theirs.transform));
  EXPECT_LT(apart_m(mine, T), 0.01);
  EXPECT_LT(apart_deg(mine, T), 0.1);
  EXPECT_LT(apart_m(mine, theirs.transform), 0.01);
  EXPECT_LT(apart_deg(mine, theirs.transform), 0.1);
  // Our GICP with point correspondences and PCL's covariances.
  const CovarianceParams cp = pcl_covariances();
  const Eigen::Matrix4d points = register_points(scan, point_surfaces(scan, cp), P, point_surfaces(P, cp), Eigen::Isometry3d::Identity()).transform.matrix();
  std::printf("known motion, ours with point matches: %.4f m, %.4f deg from the truth; apart from PCL's %.4f m, %.4f deg\n", apart_m(points, T),
              apart_deg(points, T), apart_m(points, theirs.transform), apart_deg(points, theirs.transform));
  EXPECT_LT(apart_m(points, theirs.transform), 0.01);
  EXPECT_LT(apart_deg(points, theirs.transform), 0.1);
}

// The pair as shipped, P onto Q (docs/mapping.md), by our GICP with point correspondences
// (gicp.hpp) beside PCL's, both with PCL's settings: 20 neighbours per covariance, matches within
// 5 m. From the identity the two land within 0.1 deg, 5.6 cm apart
// in position. Which is GICP's answer: PCL's GICP started at ours stays there (ours is a fixed
// point of PCL's own algorithm), ours started at PCL's comes back to ours, and ours finds the
// same pose from every guess where PCL's answer moves with its guess by centimetres: PCL's
// optimizer stops short of the minimum of each round's objective (ours, with the same matches
// and weights, ends lower).
TEST(MappingPcl, TheShippedPairIsAFixedPointOfPclsGicp) {
  const auto [P, Q] = shipped_pair();
  EXPECT_EQ(Q.size(), 1596u);
  const CovarianceParams cp = pcl_covariances();
  const Surfaces ps = point_surfaces(P, cp), qs = point_surfaces(Q, cp);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  const auto t0 = std::chrono::steady_clock::now();
  const RegistrationResult r = register_points(P, ps, Q, qs, Eigen::Isometry3d::Identity());
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.converged);
  const Eigen::Matrix4d mine = r.transform.matrix();
  const auto theirs = brickyard::baseline::gicp(P, Q, I);
  ASSERT_TRUE(theirs.converged);
  std::printf("shipped pair from the identity: PCL GICP %.3f m, %.2f deg (%.0f ms); ours %.3f m, %.2f deg (%.0f ms, %d rounds); apart %.4f m, %.4f deg\n",
              apart_m(theirs.transform, I), apart_deg(theirs.transform, I), theirs.ms, apart_m(mine, I), apart_deg(mine, I), ms,
              r.iterations, apart_m(mine, theirs.transform), apart_deg(mine, theirs.transform));
  EXPECT_LT(apart_deg(mine, theirs.transform), 0.1);
  EXPECT_LT(apart_m(mine, theirs.transform), 0.1);
  // PCL's let run (every stopping rule tightened), for the record: it creeps a centimetre
  // towards ours and stops there too.
  const auto tight = brickyard::baseline::gicp_tight(P, Q, I);
  std::printf("PCL GICP with every stopping rule tightened: %.5f m, %.5f deg from its answer with the baseline's settings, %.5f m, %.5f deg from ours (%.0f ms)\n",
              apart_m(tight.transform, theirs.transform), apart_deg(tight.transform, theirs.transform), apart_m(tight.transform, mine), apart_deg(tight.transform, mine), tight.ms);
  // After one round each, with the same matches (at the identity) and weights: the round's
  // objective per match at PCL's pose and at ours.
  const auto theirs1 = brickyard::baseline::gicp(P, Q, I, 1);
  PointRegistrationParams one;
  one.max_iterations = 1;
  const Eigen::Isometry3d mine1 = register_points(P, ps, Q, qs, Eigen::Isometry3d::Identity(), one).transform;
  auto round_objective = [&](const Eigen::Isometry3d& T) {
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < P.size(); ++i) {
      std::size_t best = Q.size();
      float best_d2 = 25;  // 5 m
      for (std::size_t j = 0; j < Q.size(); ++j)
        if (const float d2 = (Q[j] - P[i]).squaredNorm(); d2 < best_d2) best_d2 = d2, best = j;
      if (best == Q.size()) continue;
      const Eigen::Matrix3d W = (covariance_of(qs[best]) + covariance_of(ps[i])).cast<double>().inverse();
      const Eigen::Vector3d d = T * P[i].cast<double>() - Q[best].cast<double>();
      sum += d.dot(W * d), ++n;
    }
    return sum / n;
  };
  const double at_theirs = round_objective(Eigen::Isometry3d(theirs1.transform)), at_mine = round_objective(mine1);
  std::printf("the first round's objective per match: %.4f at the identity, %.4f at PCL's pose after it, %.4f at ours\n",
              round_objective(Eigen::Isometry3d::Identity()), at_theirs, at_mine);
  EXPECT_LT(at_mine, at_theirs);
  // The voxelized registration (the car's) on this pair, for the record.
  const Eigen::Matrix4d voxels = ours(P, Q, false);
  std::printf("the voxelized registration: %.3f m, %.2f deg from PCL's\n", apart_m(voxels, theirs.transform), apart_deg(voxels, theirs.transform));
  // PCL's GICP from ours: it stays (1 cm, 0.1 deg: the bound).
  const auto theirs_from_mine = brickyard::baseline::gicp(P, Q, mine);
  std::printf("PCL GICP started at ours moves it %.4f m, %.4f deg\n", apart_m(theirs_from_mine.transform, mine),
              apart_deg(theirs_from_mine.transform, mine));
  EXPECT_LT(apart_m(theirs_from_mine.transform, mine), 0.01);
  EXPECT_LT(apart_deg(theirs_from_mine.transform, mine), 0.1);
  // Ours from PCL's answer: back to ours.
  const Eigen::Matrix4d back = register_points(P, ps, Q, qs, Eigen::Isometry3d(theirs.transform)).transform.matrix();
  std::printf("ours started at PCL's answer ends %.4f m, %.4f deg from ours\n", apart_m(back, mine), apart_deg(back, mine));
  EXPECT_LT(apart_m(back, mine), 1e-3);
  // Guesses 10-40 cm off: ours finds the same pose; PCL's spread is printed.
  double ours_spread = 0, pcl_spread = 0;
  for (const double d : {0.1, 0.2, 0.4}) {
    Eigen::Matrix4d guess = I;
    guess(0, 3) = d;
    guess(1, 3) = -d;
    const Eigen::Matrix4d o = register_points(P, ps, Q, qs, Eigen::Isometry3d(guess)).transform.matrix();
    ours_spread = std::max(ours_spread, apart_m(o, mine));
    pcl_spread = std::max(pcl_spread, apart_m(brickyard::baseline::gicp(P, Q, guess).transform, theirs.transform));
  }
  std::printf("from guesses 0.14-0.57 m off: ours within %.4f m of its answer, PCL's within %.4f m of its\n", ours_spread, pcl_spread);
  EXPECT_LT(ours_spread, 1e-3);
}

// The same pair in 27 frames (turned 0, 30 and 90 deg about z, moved up to 20 m in x and y):
// one registration problem, each answer mapped back to the file's frame. On this pair GICP's
// answer holds only so far (Q: 1,596 points over 140 m, matches that move by whole points):
// ours lands within about 1 cm and 0.06 deg of itself in every frame, and PCL's GICP started at
// ours stays there; PCL's answer from the identity moves with the frame by more than ten times
// that (its BFGS ends its rounds with no progress, not at the round's minimum). The issue's "within
// 1 cm / 0.1 deg of PCL's" asks more than PCL's own answer holds (docs/mapping.md).
TEST(MappingPcl, TheShippedPairInTwentySevenFrames) {
  const auto [P, Q] = shipped_pair();
  const CovarianceParams cp = pcl_covariances();
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d ours0 = I, pcl0 = I;
  double ours_m = 0, ours_deg = 0, stays_m = 0, stays_deg = 0, pcl_m = 0, pcl_deg = 0, apart_worst_m = 0, apart_worst_deg = 0;
  for (const double yaw : {0.0, 30.0, 90.0})
    for (const double x : {0.0, -20.0, 20.0})
      for (const double y : {0.0, -20.0, 20.0}) {
        Eigen::Isometry3d C = Eigen::Isometry3d::Identity();  // the frame's points from the file's
        C.rotate(Eigen::AngleAxisd(yaw * M_PI / 180, Eigen::Vector3d::UnitZ()));
        C.pretranslate(Eigen::Vector3d(x, y, 0));
        Points Pc, Qc;
        for (const auto& p : P) Pc.push_back((C * p.cast<double>()).cast<float>());
        for (const auto& q : Q) Qc.push_back((C * q.cast<double>()).cast<float>());
        const RegistrationResult r = register_points(Pc, point_surfaces(Pc, cp), Qc, point_surfaces(Qc, cp), Eigen::Isometry3d::Identity());
        EXPECT_TRUE(r.converged) << yaw << " deg, " << x << ", " << y;
        const auto theirs = brickyard::baseline::gicp(Pc, Qc, I);
        const auto stays = brickyard::baseline::gicp(Pc, Qc, r.transform.matrix());
        stays_m = std::max(stays_m, apart_m(stays.transform, r.transform.matrix()));
        stays_deg = std::max(stays_deg, apart_deg(stays.transform, r.transform.matrix()));
        const Eigen::Matrix4d mine = C.inverse().matrix() * r.transform.matrix() * C.matrix();
        const Eigen::Matrix4d pcl = C.inverse().matrix() * theirs.transform * C.matrix();
        apart_worst_m = std::max(apart_worst_m, apart_m(pcl, mine)), apart_worst_deg = std::max(apart_worst_deg, apart_deg(pcl, mine));
        if (yaw == 0 && x == 0 && y == 0) ours0 = mine, pcl0 = pcl;
        ours_m = std::max(ours_m, apart_m(mine, ours0)), ours_deg = std::max(ours_deg, apart_deg(mine, ours0));
        pcl_m = std::max(pcl_m, apart_m(pcl, pcl0)), pcl_deg = std::max(pcl_deg, apart_deg(pcl, pcl0));
      }
  std::printf("the shipped pair in 27 frames, worst: ours from ours in the file's frame %.4f m, %.4f deg; PCL's from PCL's %.4f m, %.4f deg; "
              "PCL started at ours moves it %.4f m, %.4f deg; PCL's and ours from the same frame %.4f m, %.4f deg apart\n",
              ours_m, ours_deg, pcl_m, pcl_deg, stays_m, stays_deg, apart_worst_m, apart_worst_deg);
  EXPECT_LT(ours_m, 0.015);  // 9.8 mm in docs/mapping.md's run: room for another libm's last bits
  EXPECT_LT(ours_deg, 0.1);
  EXPECT_LT(stays_m, 0.01);
  EXPECT_LT(stays_deg, 0.1);
  EXPECT_GT(pcl_m, 0.05);  // the premise of docs/mapping.md: PCL's answer moves with the frame
}

// The map file is PCL's: pcl::io::loadPCDFile reads it, point for point.
TEST(MappingPcl, PclReadsTheMapFile) {
  Points pts;
  for (int i = 0; i < 500; ++i) pts.emplace_back(0.37f * i, std::sin(0.1f * i) * 5.0f, 0.01f * i);
  VoxelMap m(0.25f);
  m.add(pts, point_covariances(pts));
  const std::string path = testing::TempDir() + "map_for_pcl.pcd";
  write_pcd(path, m);
  const Points back = brickyard::baseline::load_pcd(path);
  ASSERT_EQ(back.size(), m.size());
  for (std::size_t i = 0; i < back.size(); ++i) EXPECT_TRUE(back[i].isApprox(m.voxels()[i].mean().cast<float>(), 1e-6f)) << i;
}
