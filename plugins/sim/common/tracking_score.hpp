#pragma once
// The tracker scored against the simulator's truth (issue 46): at each frame's stamp, every other
// car's centre (its footprint's, not its base_link) and speed against the confirmed track nearest
// it, by range bands from our car; a car in a band no track is near is missed; a confirmed track
// that moves and is near no car is a phantom (a wall or the ground taken for a car).
// Framework-free; sim.tracking_scorer is its adapter.
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::sim {

struct TrackingScoreParams {
  double match_radius = 3.0;                 // m: a track this near a car's centre is that car's
  std::vector<double> bands = {30, 60, 100};  // m: the bands' far ends (the first from 0)
  double moving_speed = 3.0;                 // m/s: a track this fast near no car is a phantom
  double centre_ahead = 1.45;                // m: a car's footprint centre ahead of its base_link
};

// A car's truth at t: base_link and heading, map frame, and its speed.
struct CarTruth {
  double t = 0, x = 0, y = 0, yaw = 0, speed = 0;
};

struct ScoredTrack {
  double x = 0, y = 0, speed = 0;  // map frame, m; m/s
};

class TrackingScore {
 public:
  TrackingScore(TrackingScoreParams p, std::size_t cars);
  void ours(const CarTruth& s) { keep(ours_, s); }
  // Our own pose as the car stack estimated it (optional): each track is also scored as placed by
  // the true pose instead (its position relative to the estimate, put back by the truth), which
  // leaves out what our own localization's error makes of it (a heading 0.5 degrees off moves a
  // car 50 m away by 0.44 m).
  void estimate(const CarTruth& s) { keep(estimate_, s); }
  void other(std::size_t car, const CarTruth& s) { keep(others_.at(car), s); }
  // One frame of confirmed tracks, stamped t: false when the truth does not reach t (not scored).
  bool frame(double t, const std::vector<ScoredTrack>& tracks);

  struct Band {
    double from = 0, to = 0;  // m
    std::vector<double> position_errors, speed_errors;  // m, m/s: one per car tracked in it
    std::vector<double> relative_errors;  // m: the same, placed by the true pose (with an estimate)
    std::size_t missed = 0;   // cars in it no track was near
    std::string name() const;  // "30_60"
  };
  const std::vector<Band>& bands() const { return bands_; }
  std::size_t frames() const { return frames_; }
  std::size_t phantoms() const { return phantoms_; }  // phantom tracks, summed over frames

 private:
  static void keep(std::deque<CarTruth>& h, const CarTruth& s);
  static std::optional<CarTruth> at(const std::deque<CarTruth>& h, double t);
  TrackingScoreParams p_;
  std::deque<CarTruth> ours_, estimate_;
  std::vector<std::deque<CarTruth>> others_;
  std::vector<Band> bands_;
  std::size_t frames_ = 0, phantoms_ = 0;
};

}  // namespace brickyard::sim
