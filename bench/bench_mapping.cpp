// bench_mapping: scan-to-map registration, ours (voxelized GICP, coarse to fine) beside PCL's
// GeneralizedIterativeClosestPoint on the same scans, in the same process, one thread.
// Scans: full 3-LiDAR frames of the simulated IMS (walls at both edges, a few pylons), each
// voxel-filtered at 0.25 m (as a mapping front end would; both registrations get the same
// points). The map: the frames 6, 4 and 2 m behind the scan's pose, stacked on their true
// poses. The guess: the true pose moved 0.3 m and 0.5 deg. Per scan: ours = the scan's
// surfaces + the registration (the map's voxels built once, not timed); PCL = align()
// (which works out both clouds' covariances). Prints per-scan medians, the ratios, and the error
// of each result against the truth (<= 10 ms per scan, >= 10x PCL's GICP). The map localizer's
// whole step on each frame (mapping.map_localizer: <= 10 ms a frame, issue 41) beside them.
// Exits 1 unless, on every scan, ours ends within 0.5 m and 1 deg of the truth and PCL's within
// 2 m and 2 deg (all start 0.28 m and 0.5 deg away; on a straight the scans do not fix the
// position along it, and PCL's GICP slides up to 1.4 m there): the figures of a diverged
// registration compare nothing.
// usage: bench_mapping [--quick] [--scans N]   (--quick: 2 scans, 2 runs each)
#include "mapping/common/covariances.hpp"
#include "mapping/common/map_localizer.hpp"
#include "perception/common/ground_filter.hpp"
#include "mapping/common/scan_mapper.hpp"
#include "mapping/common/vgicp.hpp"
#include "pcl_baseline.hpp"
#include "perception_scenes.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace brickyard;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

perception::Points in_world(const perception::Points& body, const Eigen::Isometry3d& world_from_body) {
  perception::Points out;
  out.reserve(body.size());
  for (const auto& p : body) out.push_back((world_from_body * p.cast<double>()).cast<float>());
  return out;
}

double err_m(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) { return (a.block<3, 1>(0, 3) - b.block<3, 1>(0, 3)).norm(); }
double err_deg(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) {
  return Eigen::AngleAxisd(Eigen::Matrix3d(a.block<3, 3>(0, 0).transpose() * b.block<3, 3>(0, 0))).angle() * 180 / M_PI;
}

// One registration's figures over the scans: per-scan time and the error against the truth.
struct Row {
  std::vector<double> ms, m, deg;
  void add(double time_ms, const Eigen::Matrix4d& found, const Eigen::Matrix4d& truth) {
    ms.push_back(time_ms);
    m.push_back(err_m(found, truth));
    deg.push_back(err_deg(found, truth));
  }
  bool found_truth(const char* name, double max_m, double max_deg) const {
    const double worst_m = *std::max_element(m.begin(), m.end()), worst_deg = *std::max_element(deg.begin(), deg.end());
    if (worst_m <= max_m && worst_deg <= max_deg) return true;
    std::fprintf(stderr, "bench_mapping: %s ended %.3f m and %.3f deg from the truth\n", name, worst_m, worst_deg);
    return false;
  }
  void print(const char* name) const {
    std::printf("%-28s %10.1f %12.3f %12.3f\n", name, median(ms), *std::max_element(m.begin(), m.end()),
                *std::max_element(deg.begin(), deg.end()));
  }
};

}  // namespace

int main(int argc, char** argv) {
  int scans = 8, runs = 5;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0) scans = 2, runs = 2;
    else if (std::strcmp(argv[i], "--scans") == 0 && i + 1 < argc) scans = std::max(1, std::atoi(argv[i + 1]));
  scenes::ImsOptions o;
  o.inner_wall = true;
  o.pylons = {{0, 0, 0.15, 0.7}};
  const scenes::Ims ims(std::string(BRICKYARD_SOURCE_DIR) + "/data", o);
  constexpr float kLeaf = 0.25f;
  Row ours, d1, pcl, ndt, thin, pcl_thin, located;
  std::vector<double> cov_ms;
  std::size_t points = 0, thin_points = 0, raw_points = 0;
  for (int k = 0; k < scans; ++k) {
    // Half the scans on the straight, half in the banked turn.
    const double s = (k % 2 ? ims.turn_s() : ims.straight_s()) + 40.0 * (k / 2);
    perception::Points map_pts;
    for (double back : {6.0, 4.0, 2.0}) {
      const scenes::Frame f = ims.frame(s - back, 0.5, 100 + k);
      const perception::Points w = in_world(perception::voxel_filter(f.points, kLeaf), f.world_from_body);
      map_pts.insert(map_pts.end(), w.begin(), w.end());
    }
    const scenes::Frame f = ims.frame(s, 0.5, 200 + k);
    raw_points += f.points.size();
    const perception::Points scan = perception::voxel_filter(f.points, kLeaf);
    points += scan.size();
    Eigen::Isometry3d guess = f.world_from_body;
    guess.translate(Eigen::Vector3d(0.2, -0.2, 0.05));
    guess.rotate(Eigen::AngleAxisd(0.5 * M_PI / 180, Eigen::Vector3d::UnitZ()));
    const Eigen::Matrix4d truth = f.world_from_body.matrix();
    // Ours: the map's voxels once; per scan, its surfaces and the registration.
    const mapping::Covariances map_covs = mapping::point_covariances(map_pts);
    mapping::VoxelMap coarse(1.0f), fine(0.25f);
    coarse.add(map_pts, map_covs);
    fine.add(map_pts, map_covs);
    mapping::RegistrationResult r, r1;
    std::vector<double> t, tc, t1;
    // DIRECT1 as the scan mapper runs it (each point's own voxel, its iteration limit and
    // convergence); DIRECT7 to the defaults' tighter convergence.
    const mapping::RegistrationParams direct1 = mapping::ScanMapperParams{}.registration;
    for (int run = 0; run < runs; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      const mapping::Surfaces surfaces = mapping::point_surfaces(scan);
      const auto ta = std::chrono::steady_clock::now();
      r = mapping::register_scan(scan, surfaces, {&coarse, &fine}, guess);
      const auto tb = std::chrono::steady_clock::now();
      r1 = mapping::register_scan(scan, surfaces, {&coarse, &fine}, guess, direct1);
      const auto te = std::chrono::steady_clock::now();
      t.push_back(std::chrono::duration<double, std::milli>(tb - t0).count());
      tc.push_back(std::chrono::duration<double, std::milli>(ta - t0).count());
      t1.push_back(std::chrono::duration<double, std::milli>((ta - t0) + (te - tb)).count());
    }
    ours.add(median(t), r.transform.matrix(), truth);
    cov_ms.push_back(median(tc));
    d1.add(median(t1), r1.transform.matrix(), truth);
    const auto theirs = baseline::gicp(scan, map_pts, guess.matrix());
    pcl.add(theirs.ms, theirs.transform, truth);
    // The scan as the scan mapper thins it before registering (one point, the mean, per
    // scan_voxel: 0.4 m), ours and PCL's GICP on those same points.
    const mapping::ScanMapperParams mp;
    const perception::Points thin_scan = perception::voxel_filter(f.points, mp.scan_voxel);
    thin_points += thin_scan.size();
    mapping::RegistrationResult rt;
    std::vector<double> tt;
    for (int run = 0; run < runs; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      rt = mapping::register_scan(thin_scan, mapping::point_surfaces(thin_scan, mp.covariances), {&coarse, &fine}, guess, direct1);
      tt.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    thin.add(median(tt), rt.transform.matrix(), truth);
    const auto theirs_thin = baseline::gicp(thin_scan, map_pts, guess.matrix());
    pcl_thin.add(theirs_thin.ms, theirs_thin.transform, truth);
    // The map localizer on the whole frame as the stack hands it over: thinned, its height found
    // on the map, its surfaces, the registration, the directions it cannot tell (the map's
    // voxels built once, not timed).
    const mapping::MapLocalizer localizer(map_pts);
    mapping::Located at;
    std::vector<double> tl;
    for (int run = 0; run < runs; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      at = localizer.locate(f.points, guess);
      tl.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    located.add(median(tl), at.pose.matrix(), truth);
    const auto n = baseline::ndt(scan, map_pts, guess.matrix());
    ndt.add(n.ms, n.transform, truth);
    std::printf("scan %d (s %.0f, %zu points, map %zu): ours %.1f ms, %.3f m %.3f deg (DIRECT1 %d iterations) | PCL GICP %.1f ms, %.3f m %.3f deg\n", k, s,
                scan.size(), map_pts.size(), ours.ms.back(), ours.m.back(), ours.deg.back(), r1.iterations, pcl.ms.back(), pcl.m.back(),
                pcl.deg.back());
  }
  std::printf("\nscan-to-map registration, IMS, 3 LiDARs voxel-filtered at %.2f m (%zu points a scan on average), %d scans, one thread\n",
              kLeaf, points / scans, scans);
  std::printf("%-28s %10s %12s %12s\n", "", "ms/scan", "worst m", "worst deg");
  ours.print("ours: DIRECT7, 1 m -> 0.25 m");
  d1.print("ours: DIRECT1, as the mapper");
  std::printf("%-28s %10.1f\n", "  of which the surfaces", median(cov_ms));
  pcl.print("baseline: PCL GICP");
  ndt.print("baseline: PCL NDT (1 m)");
  std::printf("PCL GICP / ours: %.1f (DIRECT1, as the mapper), %.1f (DIRECT7)\n", median(pcl.ms) / median(d1.ms),
              median(pcl.ms) / median(ours.ms));
  std::printf("\nthe same scans thinned as the scan mapper thins them (%.2f m voxels, %zu points a scan on average)\n",
              static_cast<double>(mapping::ScanMapperParams{}.scan_voxel), thin_points / scans);
  thin.print("ours: DIRECT1, as the mapper");
  pcl_thin.print("baseline: PCL GICP");
  std::printf("PCL GICP / ours: %.1f\n", median(pcl_thin.ms) / median(thin.ms));
  std::printf("\nlocalization on a prior map (mapping.map_localizer), the whole frame (%zu points a scan on average)\n",
              raw_points / scans);
  located.print("ours: MapLocalizer::locate");
  std::printf("PCL GICP (thinned scan) / ours: %.1f\n", median(pcl_thin.ms) / median(located.ms));
  bool all = true;
  for (const auto& [row, name] : {std::pair<const Row*, const char*>{&ours, "ours (DIRECT7)"}, {&d1, "ours (DIRECT1)"},
                                  {&thin, "ours (thinned)"}, {&located, "the map localizer"}})
    all = row->found_truth(name, 0.5, 1.0) && all;
  for (const auto& [row, name] : {std::pair<const Row*, const char*>{&pcl, "PCL GICP"}, {&ndt, "PCL NDT"}, {&pcl_thin, "PCL GICP (thinned)"}})
    all = row->found_truth(name, 2.0, 2.0) && all;
  return all ? 0 : 1;
}
