#pragma once
// The stop along the last path: when the stack's commands stop (its process died, or it hangs),
// the interface brakes (dbw_watchdog.hpp) and, instead of holding the wheel at its last angle,
// steers along the last path the stack planned. Where the car is comes from the last estimate the
// stack sent, carried on by dead reckoning: the wheels' speed the drive-by-wire reports, and the
// yaw rate of the IMU where one is fed, else of the single-track model for the reported steering
// angle; the rear axle's slide in a turn included. The path tracker's law (libs/control) then
// steers as the stack's would, and the brake meets the path's own speeds within the grip. Why: a
// held wheel keeps the car on the curvature it had; the racing line's does not stay the same for
// the 100 to 300 m a stop from racing speed takes, and at 80 m/s a fraction of a degree meets the
// wall (docs/vehicle-interface.md, "The stop along the last path").
// Framework-free; times in seconds of the run's clock.
#include "control/path_tracker.hpp"
#include "stop_line.hpp"
#include "track/track.hpp"

#include <optional>
#include <vector>

namespace brickyard::vehicle_interface {

struct PathStopParams {
  double max_estimate_age_s = 0.5;  // at the trip: an older estimate is not trusted to start from
  double max_path_age_s = 2.0;      // at the trip: an older path is not followed
  // The stop's deceleration where nothing asks for more (the watchdog's, if higher). Harder than
  // the watchdog's held-wheel stop: the estimate's heading error at the trip (a few tenths of a
  // degree) carries the car off the path by that angle times the stop's length, so the stop is
  // kept short; the friction circle below bounds it in turns.
  double decel_mps2 = 10;
  double gyro_fresh_s = 0.05;       // a yaw rate from the IMU this old or newer is the car's
  // The stop brakes at least as the watchdog's does, harder where the path's own speeds ahead ask
  // for it (a turn the stack would have braked for) or where the path left is shorter than the
  // stop (it ends this far before the path's end), up to max_decel_mps2; and never harder than the
  // grip the turn leaves (the tracker's friction circle, the vehicle file's): the racing line takes
  // a turn at the limit, and braking there spins the car.
  double end_margin_m = 40;
  double max_decel_mps2 = 12;
  StopLineParams line;  // with the track's map: the room kept to its edges (stop_line.hpp)
};

// What the stop asks of the car now.
struct StopCommand {
  double steer = 0;  // road-wheel angle, rad
  double decel = 0;  // m/s^2, by the brakes
};

class PathStop {
 public:
  PathStop(control::TrackerParams tracker, PathStopParams p) : tracker_(tracker), p_(p) {}

  // The stack's newest path (its stamp: seconds of the run's clock) and estimate (stamped by its
  // `time`).
  void path(double stamp, std::vector<control::PathPoint> points);
  void estimate(const control::CarState& car) { estimate_ = car; }
  // The IMU's yaw rate (rad/s, about the car's up axis): while fresh, the dead reckoning turns
  // by it rather than by the model (a banked turn, tyres the model does not know).
  void gyro(double stamp, double yaw_rate) { gyro_stamp_ = stamp, gyro_ = yaw_rate; }
  // The track's map: the stop's line keeps room to its edges (stop_line.hpp). Without one the
  // stop follows the path as it is.
  void map(track::Track track) { track_.emplace(std::move(track)); }
  bool has_map() const { return track_.has_value(); }

  // The commands went stale at `now`: the dead reckoning starts from the last estimate. False (and
  // no steering given) when there is none, or the estimate or the path is too old.
  bool begin(double now);
  bool active() const { return active_; }
  void end() { active_ = false; }

  // The stop now: the pose carried on from the last call with the car's speed `v` (m/s) and its
  // road-wheel angle `delta` (rad) as reported; the deceleration at least decel_mps2 and `least`
  // (the watchdog's) where the grip allows.
  StopCommand step(double now, double v, double delta, double least);

  // Where the dead reckoning has the car, and the line it steers along (for tests and the log).
  const control::CarState& pose() const { return pose_; }
  const std::vector<control::PathPoint>& line() const { return line_; }

 private:
  // The pose carried on by dt at speed v with the wheel at delta: the single-track model's lateral
  // speed and yaw rate (the car's own dynamics: a yaw that lags the wheel, the rear axle's slide
  // in a turn, 1.7 m/s at 59 m/s in IMS's turns), the steady turn below kDynamicFrom; with a
  // fresh gyro, its yaw rate and the steady slide that goes with it.
  void carry(double dt, double v, double delta);
  void carry_on_gyro(double dt, double v);
  void move(double dt, double v, double yaw_rate, double sideways);
  static constexpr double kDynamicFrom = 5;  // m/s
  static constexpr double kPiece_s = 0.002;
  std::size_t nearest_point() const;  // the line's point nearest the car
  double deceleration(double v, double least) const;

  control::PathTracker tracker_;
  PathStopParams p_;
  std::vector<control::PathPoint> path_, line_;  // the stack's newest; the one this stop follows
  std::optional<track::Track> track_;
  double path_stamp_ = -1e300;
  control::CarState estimate_{.time = -1e300}, pose_;
  double pose_t_ = 0;
  double lateral_ = 0, yaw_rate_ = 0;  // the centre of gravity's sideways speed, the yaw rate
  double gyro_stamp_ = -1e300, gyro_ = 0;
  bool active_ = false;
};

// The yaw rate of the single-track model's steady turn at road-wheel angle `delta` and speed v:
// v kappa with delta = L kappa + K_v v^2 kappa (lateral_lqr.hpp's steady_steer, inverted).
double steady_yaw_rate(const control::LateralModel& car, double delta, double v);

}  // namespace brickyard::vehicle_interface
