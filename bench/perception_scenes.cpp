#include "perception_scenes.hpp"

#include "sim/common/perception_score.hpp"
#include "vehicle/vehicle.hpp"

#include <cmath>

namespace brickyard::scenes {

using namespace brickyard::sim;

namespace {

constexpr double kDeg = M_PI / 180;

// One of the AV-21's three Hydras (front, and two rear-facing at +/-120 deg), placed as the
// vehicle file says.
LidarSpec hydra(const brickyard::vehicle::Mount& m) {
  LidarSpec s;
  s.mount = Eigen::Vector3d(m.xyz[0], m.xyz[1], m.xyz[2]);
  s.yaw = m.rpy_deg[2] * kDeg;
  s.elevations = row_elevations(32, -15, 15, "horizon", 2.0);
  return s;
}

}  // namespace

Ims::Ims(const std::string& data_dir, const ImsOptions& o) {
  WorldSpec w;
  w.line = load_centerline_csv(data_dir + "/tracks/IMS.csv");
  BankSpec b;
  b.mode = "curvature";
  b.degrees = o.bank_deg;
  b.curvature_threshold = 1e-3;  // the scenes' figures (docs/results-perception.md) were measured with it
  w.bank = bank_profile(w.line, b);
  // IMS runs counter-clockwise: the outside, and the outer wall, is on the right.
  w.walls.right = true;
  w.walls.left = o.inner_wall;
  w.walls.left_offset = 2.0;
  w.pylons = o.pylons;
  track_ = std::make_unique<Track>(w);
  const vehicle::Vehicle car = vehicle::load_vehicle(data_dir + "/vehicles/av21.json");
  for (const char* m : {"lidar_front", "lidar_left", "lidar_right"})
    lidars_.push_back(std::make_unique<LidarCaster>(*track_, hydra(car.mount(m))));
  // The first 300 m run of each kind, in 5 m steps.
  const double full = std::abs(o.bank_deg) * kDeg;
  auto run_of = [&](auto pred) {
    for (double s0 = 0; s0 < track_->length(); s0 += 5) {
      bool all = true;
      for (double s = s0; all && s < s0 + 300; s += 5) {
        const Frenet f = track_->at(track_->wrap_s(s), 0);
        all = pred(std::abs(track_->bank(f.seg, f.u)));
      }
      if (all) return s0;
    }
    return 0.0;
  };
  straight_s_ = run_of([](double b) { return b < 1e-9; });
  turn_s_ = run_of([&](double b) { return b > full - 1e-6; });
}

Eigen::Isometry3d Ims::pose(double s, double d) const {
  const Frenet f = track_->at(track_->wrap_s(s), d);
  const Eigen::Vector2d p = track_->position(f), g = track_->road_gradient(f);
  const double yaw = track_->heading(f), c = std::cos(yaw), sn = std::sin(yaw);
  const double pitch = -std::atan(g.x() * c + g.y() * sn), roll = std::atan(-g.x() * sn + g.y() * c);
  return Eigen::Translation3d(p.x(), p.y(), track_->road_z(f)) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

Frame Ims::frame(double s, double d, std::uint64_t seed) const {
  Frame fr;
  fr.s = s;
  fr.d = d;
  fr.world_from_body = pose(s, d);
  Rng rng(seed);
  const int seg = track_->at(track_->wrap_s(s), d).seg;
  for (const auto& l : lidars_) {
    PointBuffers b;
    b.record_surface = true;
    l->scan(fr.world_from_body, seg, rng, 1.0, b);
    const LidarSpec& sp = l->spec();
    const Eigen::Isometry3f t = (Eigen::Translation3d(sp.mount) * Eigen::AngleAxisd(sp.yaw, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(sp.pitch, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(sp.roll, Eigen::Vector3d::UnitX()))
                                    .cast<float>();
    for (std::size_t i = 0; i < b.x.size(); ++i) fr.points.push_back(t * Eigen::Vector3f(b.x[i], b.y[i], b.z[i]));
    fr.surface.insert(fr.surface.end(), b.surface.begin(), b.surface.end());
    fr.scans.push_back({t.cast<double>(), std::move(b.x), std::move(b.y), std::move(b.z), std::move(b.intensity)});
  }
  return fr;
}

double Ims::wall_y(const Eigen::Isometry3d& world_from_body, int side) const {
  return wall_y_in_body(*track_, world_from_body, side);
}

Eigen::Vector3d Ims::pylon_in_body(const Eigen::Isometry3d& world_from_body, std::size_t i) const {
  return sim::pylon_in_body(*track_, world_from_body, i);
}

}  // namespace brickyard::scenes
