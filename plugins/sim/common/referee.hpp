#pragma once
// The referee's bookkeeping from ground truth and the track: laps and lap times, speed, wall
// contacts, track-limit violations, clearances to walls and pylons, and localization error.
// Framework-free; the referee node feeds it and reports its figures as metrics.
#include "track.hpp"

#include <deque>
#include <limits>
#include <vector>

namespace brickyard::sim {

// The car's plan-view rectangle relative to base_link (rear-axle centre): the vehicle file's
// front, rear and half_width (libs/vehicle), unless the referee's parameters override them.
struct Footprint {
  double front = 0;       // m ahead of the rear axle
  double rear = 0;        // m behind it
  double half_width = 0;  // m
};

struct TruthSample {
  double t = 0, x = 0, y = 0, yaw = 0, speed = 0;
};

class Referee {
 public:
  Referee(const Track& track, Footprint fp);

  struct Events {
    bool lap_completed = false, wall_contact = false, track_violation = false, obstacle_hit = false;
  };
  Events update(const TruthSample& s);
  // An estimate of the position at time t: compared with the truth interpolated at t.
  // Returns false (and counts nothing) when t is outside the truth history.
  bool localization(double t, double x, double y);

  int laps_completed() const { return static_cast<int>(lap_times_.size()); }
  const std::vector<double>& lap_times() const { return lap_times_; }
  double max_speed() const { return max_speed_; }
  int wall_contacts() const { return wall_contacts_; }
  int track_violations() const { return track_violations_; }
  double min_wall_clearance() const { return min_wall_clearance_; }
  double min_wall_clearance_s() const { return min_wall_clearance_s_; }  // where (centre line's s); NaN: no sample
  int obstacles_hit() const { return obstacles_hit_; }
  double obstacle_min_clearance() const { return obstacle_min_clearance_; }  // +inf: no pylons
  double localization_rmse() const;                                           // NaN: no samples
  double localization_max_error() const;
  std::size_t localization_samples() const { return loc_n_; }
  double last_wall_clearance() const { return last_wall_clearance_; }
  double s() const { return last_s_; }
  double t() const { return last_t_; }
  // Seconds the car has been standing (below 0.5 m/s) at the last sample; 0 while it moves, and
  // before it first moved (a car waiting at the start is not stopped short).
  double stopped_for() const { return moved_ ? last_t_ - last_moving_t_ : 0.0; }

 private:
  const Track& track_;
  Footprint fp_;
  int hint_ = -1;
  bool started_ = false, timing_ = false;
  double last_s_ = 0, last_t_ = 0, lap_start_ = 0;
  std::vector<double> lap_times_;
  double max_speed_ = 0;
  int wall_contacts_ = 0, track_violations_ = 0, obstacles_hit_ = 0;
  bool in_contact_ = false, in_violation_ = false;
  bool moved_ = false;
  double last_moving_t_ = 0;
  std::vector<bool> pylon_hit_;
  double min_wall_clearance_ = std::numeric_limits<double>::infinity();
  double min_wall_clearance_s_ = std::numeric_limits<double>::quiet_NaN();
  double last_wall_clearance_ = std::numeric_limits<double>::infinity();
  double obstacle_min_clearance_ = std::numeric_limits<double>::infinity();
  std::deque<TruthSample> history_;
  double loc_sq_ = 0, loc_max_ = 0;
  std::size_t loc_n_ = 0;
};

}  // namespace brickyard::sim
