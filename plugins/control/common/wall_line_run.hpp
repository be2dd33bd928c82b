#pragma once
// control.wall_follower's offset_line law over a run, framework-free: the map (a track built again
// only for another one), the pose estimates and the planner's path that place the map's edges and
// the path round the car at a wall frame's stamp, the IMU's motion that carries the line between
// frames and from a frame's stamp to now, each wall frame's line and the wall it follows, and the
// summary's counts. The plugin converts the messages and publishes.
#include "mapped_wall.hpp"
#include "wall_line.hpp"

#include "math/estimate_history.hpp"
#include "track/track.hpp"
#include "vehicle/vehicle.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace brickyard::control {

// The wall a frame's line follows, as the 'followed' WallEstimate tells it.
struct FollowedWall {
  std::int64_t stamp_ns = 0;         // the wall frame's
  std::vector<double> coefficients;  // the followed wall's fit (vehicle frame); empty: no wall
  double distance = NAN;             // the gap kept, signed (left positive); NaN: no wall
  bool valid = false;                // there is a line to follow (a held one included)
};

class WallLineRun {
 public:
  WallLineRun() = default;
  // The follower of offset lines for `car`: the path tracker's LQR (steering cost r_steer) within
  // the law's steering limit, at its speed gain and braking, with feedforward pedals (within the
  // friction circle: it brakes in turns); the line's speeds at the law's a_lat and its curvature
  // at most what steer_margin of the steering limit turns.
  WallLineRun(WallLineParams line, const WallFollowerParams& law, double r_steer, double steer_margin, const vehicle::Vehicle& car);

  // A map. The map source republishes the same map every second: a track is built again only for
  // another centre line or widths. Returns what is wrong with an unusable one (the last track
  // stays), else empty.
  std::string map(track::TrackGeometry geometry);
  void estimate(std::int64_t stamp_ns, const math::PlanarPose& pose) { poses_.add(stamp_ns, pose, {}); }
  void path(std::vector<PathPoint> map_frame) { planned_ = std::move(map_frame); }  // the planner's newest
  // An IMU sample: the car's motion since the last one (at `speed`) carries the line.
  void imu(std::int64_t stamp_ns, double yaw_rate, double speed);
  // A wall estimate of side i (0 left, 1 right): its fit, valid only with a finite distance y(0).
  void wall(int i, WallView view, double distance, std::int64_t stamp_ns);
  // After a step's inputs, when a wall came: the frame's line, set at time t and carried from the
  // frame's stamp to now. The map's edges and the planner's path are placed round the car with
  // the estimate nearest that stamp (not one interpolated to it: the line's calibration was tuned
  // on it); `calibrating` (the manager drives the path) with a map: the walls' place from the
  // edges is learnt.
  std::optional<FollowedWall> frame(double t, bool calibrating);

  bool moving() const { return imu_t_ >= 0; }  // an IMU sample came: the car is carried between frames
  void engage(double t, double speed) { line_.engage(t, speed); }
  Command control(double t, double speed) { return line_.control(t, speed, yaw_rate_); }
  // The summary's counts, in the order they are reported: switches, frames per side and held,
  // and where the lines came from.
  std::vector<std::pair<std::string, double>> metrics() const;

 private:
  static constexpr std::size_t kHistory = 64;
  WallLineFollower line_;
  WallLineParams params_;
  math::EstimateHistory<std::monostate> poses_{kHistory};
  MotionHistory motion_{kHistory};  // to carry a line from its wall frame's stamp on
  std::unique_ptr<track::Track> track_;
  int hint_ = -1;
  std::vector<PathPoint> planned_;  // map frame
  WallView last_[2];                // left, right
  bool fresh_ = false;              // a wall came since the last frame
  std::int64_t stamp_ = 0;          // the newest of those walls' stamps
  double imu_t_ = -1, yaw_rate_ = 0;
  std::uint64_t frames_[2] = {0, 0}, held_ = 0;
};

}  // namespace brickyard::control
