#pragma once
// Wall following on road courses, framework-free: the line a gap inward of a fitted
// wall, as a path in the vehicle frame that the car stack's path tracker (libs/control) follows.
//
// Why not the paper's law alone: u_w = w_θ y′(L) + w_d (d_w − d_gap) keeps 8 m from one wall with
// gains tuned on IMS's 300 m turns. In a hairpin whose outer wall bends at 15 m, the line 8 m
// inside it is tighter than the car can turn, and a fixed side has no wall in half the turns of
// a road course. Here:
//  - Which wall: the nearer valid one, left or right, at take-over; kept while it is valid; when
//    it is lost, the other if that one is valid (choose_wall).
//  - The gap: the car's own distance to that wall when it takes it, within [min_gap, max_gap], so
//    the take-over asks for no lateral move; cut where the wall bends so tight that the line the
//    gap inside it would be tighter than the car's steering allows (line_gap).
//  - The line: the wall polynomial offset by the gap along its normal over the wall's fitted
//    extent, continued on its tangent beyond; each point's speed is what its curvature allows at
//    a_lat (offset_line). The path tracker brakes ahead of the slowest point it sees.
//  - Between wall frames the car's motion (wheel speed, IMU yaw rate) carries its pose along the
//    line (LineOdometry); a lost wall leaves the last line to follow for hold_s, during which either
//    wall may come back, before the follower gives up (brakes and reports no wall).
#include "control/path_tracker.hpp"
#include "wall_follower.hpp"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

namespace brickyard::control {

struct WallLineParams {
  double min_gap = 2.5;        // m: never closer to the wall than this (half the car and a margin)
  double max_gap = 8.0;        // m: the paper's gap, the most kept
  double step = 1.0;           // m between the line's points
  double behind = 5.0;         // m of line behind the car (the tracker's curvature window needs it)
  double extend = 20.0;        // m of line past the wall's seen end, on its tangent
  double a_lat = 10;           // m/s^2: each point's speed at most sqrt(a_lat / curvature)
  double max_curvature = 0.1;  // 1/m: the line never tighter (the plugin: the car's steering, with a margin)
  double hold_s = 1.0;         // s: a lost wall's last line is followed this long
  double max_distance = 20;    // m: a fit farther from the car than this is not a wall to follow
                               // (across a hairpin, the wall of the way back)
  double map_behind = 10, map_ahead = 250;  // m of the map's edge taken round the car
  double registration_smoothing = 0.3;      // share of a frame's registration taken (the rest: the last)
  double calibration_bin = 10;              // m of s per learnt wall-to-edge registration
  double smooth_half = 5;                   // m: the mapped line is averaged over +-this, at `step`
  // Steering at most this times what holds the car's grip (the tracker's) in a steady turn.
  double grip_steer_margin = 1.5;
};

// A point of a wall or edge as a polyline, vehicle frame.
struct EdgePoint {
  double x = 0, y = 0;
};

// Laying the map's edge onto the LiDAR's wall (mapped_wall.hpp).
struct EdgeRegistration {
  double shift = 0;  // m across (vehicle y) after the turn
  double turn = 0;   // rad about the car
  double rms = 0;    // m: what the turn and shift leave between the edge and the LiDAR's wall
  int points = 0;
  bool ok = false;
};

struct RegistrationParams {
  double from = 0, to = 15;   // m of vehicle x where the LiDAR's wall is taken (within its fitted extent)
  double max_shift = 3.0;     // m: a larger correction is not the estimate's drift
  double max_turn = 0.2;      // rad
  double max_rms = 0.4;       // m: the shapes must agree
  int min_points = 3;         // edge points within the stretch
};

// A fit that is a wall on `side` (-1 right, +1 left): valid, finite, passing the car on that side
// (a detector of the left wall may take the right one, round a turn or with no left wall at
// all), within max_distance.
bool usable(const WallView& w, int side, double max_distance);

// -1 right, +1 left, 0 none: the wall to follow given the one followed now (0 at take-over) and
// the car's distances |y(0)| to the valid ones.
int choose_wall(int following, const WallView& left, const WallView& right, double max_distance = 20);

// The gap kept to a wall on `side` whose fit the car takes at distance |y(0)|: that distance within
// [min_gap, max_gap], cut so the line stays within max_curvature where the wall bends away from it.
double line_gap(const WallView& wall, int side, double distance, const WallLineParams& p);

// The line `gap` inward of the wall on `side`, from `behind` the car to `extend` past the wall's
// seen end, each point with the speed its curvature allows (capped at v_cap).
std::vector<PathPoint> offset_line(const WallView& wall, int side, double gap, double v_cap, const WallLineParams& p);

// The car's pose in the frame of the last line (the vehicle frame at that wall frame), carried by
// wheel speed and yaw rate; reset when a new line arrives.
class LineOdometry {
 public:
  void reset() { x_ = y_ = yaw_ = 0; }
  void advance(double dt, double speed, double yaw_rate);
  double x() const { return x_; }
  double y() const { return y_; }
  double yaw() const { return yaw_; }

 private:
  double x_ = 0, y_ = 0, yaw_ = 0;
};

// The IMU's steps of the car's motion (each ends at t and lasts dt), the last `keep` of them: a
// wall frame arrives some time after its stamp (a LiDAR frame is delivered a sweep after its
// scan), and its line, set in the vehicle frame of that stamp, is carried to now by the motion
// since.
class MotionHistory {
 public:
  explicit MotionHistory(std::size_t keep = 64) : keep_(keep) {}
  void add(double t, double dt, double speed, double yaw_rate);
  // Calls moved(dt, speed, yaw_rate) for the motion after `since`, oldest first (a step that
  // straddles it, for its part after).
  template <class F> void since(double since, F&& moved) const {
    for (const Step& m : steps_)
      if (m.t > since) moved(std::min(m.dt, m.t - since), m.speed, m.yaw_rate);
  }

 private:
  struct Step {
    double t, dt, speed, yaw_rate;
  };
  std::size_t keep_;
  std::deque<Step> steps_;
};

// The follower: chooses the wall, keeps its line, and drives it with a PathTracker. The speed
// policy (hold or reduce after take-over) is the paper's follower's (WallFollowerParams).
class WallLineFollower {
 public:
  WallLineFollower() = default;
  WallLineFollower(WallLineParams line, WallFollowerParams policy, TrackerParams tracker, RegistrationParams registration = {});
  // Take-over at time t and speed: the wall and its gap are chosen afresh at the next frame.
  void engage(double t, double speed);
  // A new frame of both walls (an unwired or unseen side: not valid), at time t; with the map's
  // edges on each side placed by the pose estimate (mapped_edge), the line follows the map's
  // edge laid onto the wall where the two agree (register_edge), else the wall's polynomial.
  // With the planner's path placed by the same estimate (`planned`, vehicle frame, with speeds),
  // the line is that path corrected by the registration, so the car goes on along the line it
  // was on, its place taken from the wall.
  //
  // Where the wall stands from the map's edge (an inner wall 2 m beyond it, a barrier set back
  // at a pit entry) is not the estimate's error: while localization is good (`calibrating`, the
  // manager's PATH) the registration of each side is learnt along the track in bins of
  // `calibration_bin` metres of `s` (the car's place on the map); while the follower drives, only
  // the registration's departure from what was learnt there (or, at a place not learnt yet, last
  // on that side) moves the planner's path.
  void walls(double t, const WallView& left, const WallView& right, const std::vector<EdgePoint>* edge_left = nullptr,
             const std::vector<EdgePoint>* edge_right = nullptr, const std::vector<PathPoint>* planned = nullptr,
             double s = 0, bool calibrating = false);
  // The car moved for dt at this speed and yaw rate since the last call.
  void moved(double dt, double speed, double yaw_rate) { odo_.advance(dt, speed, yaw_rate); }
  // The command at time t: the line followed, or full brake when there is none (lost past hold_s).
  Command control(double t, double speed, double yaw_rate);
  // -1 right, +1 left, 0: none (after a loss past hold_s); and whether the line is a held one.
  int side() const { return side_; }
  bool has_line(double t) const { return side_ != 0 && t - seen_t_ <= line_.hold_s; }
  double gap() const { return gap_; }  // the car's distance to the wall when it took it (line_gap bounds it)
  std::uint64_t switches() const { return switches_; }
  std::uint64_t planned_lines() const { return planned_; }  // the planner's path, registered
  std::uint64_t mapped_lines() const { return mapped_; }    // lines from the registered map edge
  std::uint64_t polynomial_lines() const { return poly_; }  // lines from the wall's polynomial alone
  const EdgeRegistration& registration() const { return reg_; }
  const std::vector<PathPoint>& line() const { return line_points_; }  // the last line, its wall frame's
  // The wall-to-edge registration learnt for a side (-1, +1) at s (nearest learnt bin; the side's
  // last when none): what the path's correction is taken from.
  EdgeRegistration learnt(int side, double s) const;
  std::size_t learnt_bins() const { return base_[0].size() + base_[1].size(); }

 private:
  double policy_speed(double t) const;
  WallLineParams line_;
  WallFollowerParams policy_;
  PathTracker tracker_;
  std::vector<PathPoint> line_points_;
  RegistrationParams reg_params_;
  std::map<long, EdgeRegistration> base_[2];  // per side (0 right, 1 left): bin of s -> learnt registration
  EdgeRegistration last_base_[2];
  EdgeRegistration reg_, smooth_;
  LineOdometry odo_;
  int side_ = 0;
  bool rechoose_ = true;  // the next frame chooses the wall afresh (take-over)
  double gap_ = 0, seen_t_ = -1e300, t0_ = 0, v0_ = 0;
  std::uint64_t switches_ = 0, planned_ = 0, mapped_ = 0, poly_ = 0;
};

}  // namespace brickyard::control
