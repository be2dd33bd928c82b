#include "scanner.hpp"

#include <cmath>

namespace brickyard::sim {

namespace {
constexpr double kDeg = M_PI / 180.0;
}  // namespace

LidarSpec placed_spec(LidarSpec spec, const std::array<double, 3>& mount, const std::array<double, 3>& rpy_deg,
                      const LidarRowsDeg& rows) {
  spec.mount = {mount[0], mount[1], mount[2]};
  spec.roll = rpy_deg[0] * kDeg;
  spec.pitch = rpy_deg[1] * kDeg;
  spec.yaw = rpy_deg[2] * kDeg;
  spec.h_fov = rows.h_fov_deg * kDeg;
  if (!rows.row_angles_deg.empty()) {
    for (double a : rows.row_angles_deg) spec.elevations.push_back(a * kDeg);
  } else {
    spec.elevations = row_elevations(rows.rows, rows.v_min_deg, rows.v_max_deg, rows.row_spacing, rows.horizon_exponent);
  }
  return spec;
}

Scanner::Scanner(LidarSpec spec, FaultSchedule faults, Rng rng)
    : spec_(std::move(spec)), faults_(std::move(faults)), rng_(rng) {}

void Scanner::start(WorldSpec world) {
  track_ = std::make_unique<Track>(std::move(world));
  caster_ = std::make_unique<LidarCaster>(*track_, spec_);
}

Scanner::Frame Scanner::frame(double t, const Eigen::Isometry3d& world_from_body, double x, double y,
                              const std::vector<CarBody>& cars) {
  const FaultEffect e = faults_.at(t, rng_);
  if (e.drop) {
    ++lost_;
    return Frame::lost;
  }
  if (e.freeze && frames_ > 0) return Frame::repeat;
  buf_.clear();
  hint_ = track_->project(x, y, hint_).seg;
  rays_ += caster_->scan(world_from_body, hint_, rng_, e.noise_factor, buf_, cars);
  points_ += buf_.x.size();
  for (const auto* v : {&buf_.x, &buf_.y, &buf_.z, &buf_.intensity}) digest_.add(v->data(), v->size() * sizeof(float));
  ++frames_;
  return Frame::fresh;
}

}  // namespace brickyard::sim
