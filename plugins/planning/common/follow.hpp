#pragma once
// Other cars as the planner takes them (issue 46): a car the tracker follows is not a pylon. Its
// detections are left out of the obstacles the road graph plans round (planned round as if it
// stood still, a car 90 % of our pace ahead was swerved round or braked for as a wall), and the
// path's speeds are capped to follow it when it is in the path's way: the gap between the bumpers
// closes no faster than braking at `decel` brings our speed down to its own at `min_gap` plus
// `headway_s` of its speed (v <= sqrt(v_car² + 2 decel (gap - wanted gap))), and never below its
// speed while the gap is wider than wanted. Passing is the road graph's in space and time: not
// yet (docs/tracking.md). Framework-free.
#include "plan_frames.hpp"
#include "road_graph.hpp"

#include <vector>

namespace brickyard::planning {

struct FollowParams {
  double headway_s = 1.0;     // s of the followed car's speed kept behind it, beyond min_gap
  double min_gap = 10.0;      // m between the bumpers at any speed
  double decel = 6.0;         // m/s²: the braking the cap allows to close the gap (the AV-21 has ~15)
  double moving_speed = 3.0;  // m/s: a track slower than this is left to the obstacles (a pylon)
  double car_length = 2.0;    // m: a shorter track is no car (a pylon)
  double match_radius = 4.0;  // m: a detection this near a moving car is that car's
  double side_margin = 1.5;   // m between the cars' sides below which a car is in the path's way (the IAC's
                              // lateral gap alongside: nearer than that, a car is followed, not passed)
};

// An object the tracker follows, map frame: its centre, velocity and its speed's spread, size.
struct MovingCar {
  double x = 0, y = 0, vx = 0, vy = 0;
  double speed_sigma = 0;
  double length = 4.9, width = 1.94;
  double speed() const;
  // A car (its length a car's: the tracker makes cars whole), surely moving (its speed two
  // spreads above moving_speed): a pylon's young track, its speed a guess, stays a pylon.
  bool moving(const FollowParams& p) const;
};

// The detections (vehicle frame of `at`) not a moving car's.
std::vector<Detection> not_moving_cars(const StampedPose& at, const std::vector<Detection>& list, const std::vector<MovingCar>& cars,
                                       const FollowParams& p);

// The cap on our speed now, to follow the first moving car in the path's way (the path from the
// car on, map frame, its d the racing line's; `front`: our bumper ahead of base_link,
// `half_width`: ours): a car whose offset from the racing line the path comes within the cars'
// half widths and side_margin of, where the car will be while we close on it. None in the way:
// +inf. `gap_out` (when not null): the gap between the bumpers to that car, m (+inf: none).
double follow_speed(const std::vector<PathSample>& path, double x, double y, double our_speed, double front, double half_width,
                    const std::vector<MovingCar>& cars, const FollowParams& p, double* gap_out = nullptr);

}  // namespace brickyard::planning
