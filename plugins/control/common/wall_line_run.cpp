#include "wall_line_run.hpp"

#include "control/vehicle_tracking.hpp"

#include <algorithm>
#include <exception>

namespace brickyard::control {

WallLineRun::WallLineRun(WallLineParams line, const WallFollowerParams& law, double r_steer, double steer_margin,
                         const vehicle::Vehicle& car) {
  TrackerParams tp;
  apply_vehicle(tp, car);
  tp.max_steer = law.max_steer;
  tp.steer_law = SteerLaw::lqr;
  tp.lqr.r_steer = r_steer;
  tp.speed_gain = law.speed_gain;
  tp.decel = law.decel;
  tp.pedal_law = PedalLaw::feedforward;
  line.a_lat = law.a_lat;
  line.max_curvature = std::tan(steer_margin * law.max_steer) / car.wheelbase;
  line_ = WallLineFollower(line, law, tp);
  params_ = line;
}

std::string WallLineRun::map(track::TrackGeometry geometry) {
  if (track_) {
    const auto& g = track_->geometry().line;
    const auto& m = geometry.line;
    if (m.x == g.x && m.y == g.y && m.width_left == g.width_left && m.width_right == g.width_right) return {};
  }
  try {
    track_ = std::make_unique<track::Track>(std::move(geometry));
    hint_ = -1;
  } catch (const std::exception& e) {
    return std::string("map ignored: ") + e.what();
  }
  return {};
}

void WallLineRun::imu(std::int64_t stamp_ns, double yaw_rate, double speed) {
  const double ts = static_cast<double>(stamp_ns) * 1e-9;
  if (imu_t_ >= 0 && ts > imu_t_) {
    line_.moved(ts - imu_t_, speed, yaw_rate);
    motion_.add(ts, ts - imu_t_, speed, yaw_rate);
  }
  imu_t_ = ts;
  yaw_rate_ = yaw_rate;
}

void WallLineRun::wall(int i, WallView view, double distance, std::int64_t stamp_ns) {
  last_[i] = std::move(view);
  last_[i].valid = last_[i].valid && std::isfinite(distance);
  stamp_ = std::max(stamp_, stamp_ns);
  fresh_ = true;
}

std::optional<FollowedWall> WallLineRun::frame(double t, bool calibrating) {
  if (!fresh_) return std::nullopt;
  const std::int64_t stamp = stamp_;
  fresh_ = false;
  stamp_ = 0;
  // A wall frame is the car's surroundings at its stamp, which may be some time ago (a LiDAR's
  // frame is delivered when its sweep is over, docs/architecture.md).
  const math::PlanarPose* pose = poses_.empty() ? nullptr : &poses_.nearest(stamp)->pose;
  std::vector<EdgePoint> edges[2];
  const bool mapped = track_ && pose;
  if (mapped)
    for (int i = 0; i < 2; ++i)
      edges[i] = mapped_edge(*track_, i == 0 ? 1 : -1, pose->x, pose->y, pose->yaw, params_.map_behind, params_.map_ahead, hint_);
  std::vector<PathPoint> planned;  // the planner's path in the vehicle frame of the estimate
  if (mapped) planned = in_vehicle_frame(planned_, pose->x, pose->y, pose->yaw);
  // The car's place along the map: the follower learns there where the walls stand from the edges.
  const double s_car = mapped ? track_->project(pose->x, pose->y, hint_).s : 0.0;
  line_.walls(t, last_[0], last_[1], mapped ? &edges[0] : nullptr, mapped ? &edges[1] : nullptr,
              planned.size() >= 2 ? &planned : nullptr, s_car, mapped && calibrating);
  motion_.since(static_cast<double>(stamp) * 1e-9, [&](double dt, double v, double w) { line_.moved(dt, v, w); });
  const bool line = line_.has_line(t);
  if (line && line_.side() != 0) ++frames_[line_.side() > 0 ? 0 : 1];
  held_ += line && !last_[line_.side() > 0 ? 0 : 1].valid;
  FollowedWall f;
  f.stamp_ns = stamp;
  if (line_.side() != 0) f.coefficients = last_[line_.side() > 0 ? 0 : 1].coefficients;
  f.distance = line_.side() == 0 ? NAN : line_.side() * line_.gap();
  f.valid = line;
  return f;
}

std::vector<std::pair<std::string, double>> WallLineRun::metrics() const {
  return {{"wall_switches", static_cast<double>(line_.switches())},
          {"frames_left", static_cast<double>(frames_[0])},
          {"frames_right", static_cast<double>(frames_[1])},
          {"frames_held", static_cast<double>(held_)},
          {"lines_planned", static_cast<double>(line_.planned_lines())},
          {"wall_bins_learnt", static_cast<double>(line_.learnt_bins())},
          {"lines_mapped", static_cast<double>(line_.mapped_lines())},
          {"lines_polynomial", static_cast<double>(line_.polynomial_lines())}};
}

}  // namespace brickyard::control
