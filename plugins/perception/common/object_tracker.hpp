#pragma once
// Moving objects from frame after frame of detections (issue 46: other cars on the track), followed
// in the track's frame: s along the centre line, d across it. A car racing holds its line and its
// pace, so in (s, d) it moves at a near-constant velocity through a turn as on a straight, where in
// the map frame it accelerates towards the turn's centre (at 50 m/s in a 400 m turn, 6 m/s^2 for
// seconds: a constant-velocity model there lags and loses it from its gate). Each detection, put
// in the map frame by the car's pose and then on the track, is associated with a track by a gate
// on its innovation (chi-square, 2 dof) and the cheapest pairs first. A track is two Kalman
// filters on s, d, ds/dt, dd/dt, d2s/dt2 mixed as an interacting multiple model (IMM): a steady
// one (constant velocity, small white accelerations: a car holding its pace and line, its speed
// smooth) and a maneuvering one (constant acceleration along the track with white jerk, braking
// at 15 m/s^2 or powering out for seconds; a change of line across), each weighed by how well it
// has foretold the detections; the track is their mix. Births: a detection no track takes starts a tentative track, confirmed after
// `confirm_hits` hits within its first `confirm_window` frames (dropped once it cannot be);
// deaths: a confirmed one missed `max_misses` frames on end, or any whose spread grows past
// `max_sigma`. A wall and the ground never reach here (the obstacle detector leaves out what is
// longer than a car, and the ground filter the road); what stands still is a track of no speed.
// Framework-free: unit tests call it directly; the plugin (object_tracker/plugin.cpp) turns
// messages into these calls.
#include "track/track.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace brickyard::perception {

// The other cars' size (the same model as ours by default: the plugin reads the vehicle file) and
// how their parts are told (car_parts.hpp).
struct CarShape {
  double length = 4.9, width = 1.94;  // m
  double min_extent = 1.2;  // m: a detection this long or wide is (part of) a car; a pylon is not
  double fit_margin = 0.8;  // m: a car's box in our frame may exceed its size by this (turned against ours)
  double join_gap = 2.0;    // m: the parts of one car lie this close to each other
  double sensor_x = 1.9;    // m ahead of base_link: where the LiDARs look from (the faces seen face it)
};

struct TrackerParams {
  double accel_sigma = 1.0, lateral_accel_sigma = 0.5;  // m/s^2, white: the steady model, along and across
  double jerk_sigma = 5.0;              // m/s^3, white: the maneuvering model along the track
  double maneuver_lateral_sigma = 5.0;  // m/s^2, white: and across it
  // Per frame, the chance a steady car starts to maneuver, and a maneuvering one settles. At 20 Hz
  // a detection's noise hides one frame's difference between the models (15 m/s^2 moves a car
  // 2 cm in 50 ms): the mode is learnt over many frames, so these are small.
  double switch_to_maneuver = 0.01;
  double switch_to_steady = 0.005;
  double meas_sigma = 0.15;          // m: a detection's position, 1 sigma, at any range
  double meas_sigma_per_m = 0.002;   // m per m of range added (a far car is fewer points)
  double gate = 13.8;                // chi-square, 2 dof, 0.999
  double birth_speed_sigma = 30;     // m/s: a new track's speed spread (its speed unknown)
  int confirm_hits = 3;              // hits within confirm_window frames confirm a track
  int confirm_window = 4;
  int max_misses = 5;                // frames on end a confirmed track may go unseen (coasting)
  double max_sigma = 3.0;            // m: a track whose position spread grows past it is dropped
  CarShape car;
  bool whole_cars = true;            // a car's parts merged and completed to its centre (car_parts.hpp)
  double road_margin = 0.5;          // m: a detection's centre this far inside the road's edges at
                                     // least, or it is not followed (a wall's stripes stand at or
                                     // beyond the edge; a car's centre is half its width inside)
};

// One detection in the vehicle frame (base_link), as the obstacle detector gives it.
struct Detection {
  double x = 0, y = 0;            // m
  double size_x = 0, size_y = 0;  // m: its extent, kept on the track
  std::vector<Eigen::Vector2d> outline;  // its footprint's hull (empty: its box's corners stand for it)
  double box_yaw = std::numeric_limits<double>::quiet_NaN();  // its sides' turn, [0, pi/2) (NaN: none)
};

// The car's pose when the frame was taken: detections go to the map frame with it.
struct EgoPose {
  double x = 0, y = 0, yaw = 0;
};

struct Track {
  std::uint32_t id = 0;
  using Vec = Eigen::Matrix<double, 5, 1>;
  using Mat = Eigen::Matrix<double, 5, 5>;
  Vec state = Vec::Zero();  // s, d (m), ds/dt, dd/dt (m/s), d2s/dt2 (m/s^2): the models' mix
  Mat cov = Mat::Identity();
  Vec model_state[2];  // each model's: steady, maneuvering
  Mat model_cov[2];
  Eigen::Vector2d mode = Eigen::Vector2d(0.5, 0.5);  // the models' probabilities
  // The same in the map frame (set after each frame): position, velocity, its speed and heading.
  Eigen::Vector2d xy = Eigen::Vector2d::Zero(), velocity = Eigen::Vector2d::Zero();
  Eigen::Matrix2d xy_cov = Eigen::Matrix2d::Identity();
  double size_x = 0, size_y = 0;
  int hits = 0, misses = 0, age = 0;  // age: frames since its birth
  bool confirmed = false;
  double speed() const { return velocity.norm(); }
  double heading() const;  // of its velocity (rad); 0 when it stands still
};

// The maneuvering model over dt, the tracker's and the prediction's: constant acceleration along
// the track whose jerk is white (`jerk`, m/s^3), constant velocity across it whose acceleration is
// white (`across`, m/s^2).
void maneuver_model(double dt, double jerk, double across, Track::Mat& F, Track::Mat& Q);

class ObjectTracker {
 public:
  // `track` must outlive the tracker.
  explicit ObjectTracker(const track::Track& track, TrackerParams p = {}) : track_(&track), p_(p) {}
  // One frame of detections taken at t (s), the car at `ego`.
  void update(double t, const EgoPose& ego, const std::vector<Detection>& detections);
  const std::vector<Track>& tracks() const { return tracks_; }
  std::uint64_t births() const { return births_; }
  std::uint64_t deaths() const { return deaths_; }
  std::uint64_t off_road() const { return off_road_; }  // detections left out: not well inside the road

 private:
  void predict(double dt);
  // The angle of the course of the track nearest f to the track's direction (none: none near,
  // slow, or not sure of its course).
  std::optional<double> course_across(const track::Frenet& f) const;
  static constexpr double kCourseRadius = 6.0;    // m: a track this near a detection lends it its course
  static constexpr double kCourseMinSpeed = 10.0;  // m/s: slower, its course is noise
  static constexpr double kCourseSpread = 0.02;    // its speed across at most this share of along, 1 sigma
  // Each detection's track (-1: none), the cheapest gated pairs first.
  std::vector<int> associate(const std::vector<Eigen::Vector2d>& z, const std::vector<double>& r) const;
  // A detection less an estimate's position, along the track the short way round the start line.
  Eigen::Vector2d innovation(const Eigen::Vector2d& z, const Track::Vec& x) const;
  void correct(Track& track, const Eigen::Vector2d& z, double r);
  void age_and_prune(const std::vector<bool>& hit);
  void birth(const Eigen::Vector2d& z, double r, const Detection& d);
  void to_map(Track& tr) const;
  // The track's models weighed by `w` as one estimate, and its spread (the models' own and their
  // differences); s the short way round.
  void weighed(const Track& tr, const Eigen::Vector2d& w, Track::Vec& x, Track::Mat& P) const;
  void mix(Track& tr) const;  // the track's state and spread from its models

  const track::Track* track_;
  TrackerParams p_;
  std::vector<Track> tracks_;
  double t_ = 0;
  bool started_ = false;
  int hint_ = -1;
  std::uint32_t next_id_ = 1;
  std::uint64_t births_ = 0, deaths_ = 0, off_road_ = 0;
};

}  // namespace brickyard::perception
