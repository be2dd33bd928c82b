#pragma once
// The paper's wall-following fallback (§III-B), framework-free:
//   u_w = w_θ · y′(d_lookahead) + w_d · (d_w − d_gap)
// y(x) is the wall's polynomial in the vehicle frame (WallEstimate), d_w = y(0). The paper writes
// it for the wall on the right with d_w and d_gap as magnitudes; here y is signed (left positive)
// and the gap is kept on the wall's side: u_w = w_θ y′(L) + w_d (d_w − side · d_gap), side −1 for
// a right wall. Too far from a right wall (d_w = −10, gap 8) gives u < 0: steer right, toward it;
// a wall curving left ahead (y′ > 0) gives u > 0: turn with it. u_w is the road-wheel angle,
// clamped to max_steer.
// Speed while it drives: `hold` the speed it took over at, or `reduce` to fallback_speed at
// `decel` (never above the speed it took over at, or restart_speed when that was slower: a car
// that had stopped); either way at most sqrt(a_lat / κ) for the wall's curvature κ at the
// look-ahead.
#include "motion/command.hpp"

#include <vector>

namespace brickyard::control {

using motion::Command;
using motion::pedals_for;

struct WallFollowerParams {
  int side = -1;               // -1: the wall on the right
  // Gains for 30 to 40 m/s with the AV-21's 2.97 m wheelbase: w_theta ~ wheelbase / lookahead
  // steers a wall's curvature out (y′(L) = L / R on an arc, the car needs wheelbase / R); w_d is
  // what a pure pursuit with a 30 m look-ahead gives per metre of offset (2 wheelbase / L²,
  // 0.007). Five times these (the first try) made the car weave and spin at 40 m/s.
  double w_theta = 0.3;        // rad per unit of wall slope
  double w_d = 0.01;           // rad per m of gap error
  double gap = 8.0;            // m kept to the wall
  double lookahead = 10.0;     // m: where the wall's slope is read
  // Above this speed the law keeps its shape but the gains follow the speed as a pure pursuit's
  // would (look-ahead x v/v0, w_theta x v0/v, w_d x (v0/v)^2): gains right at 40 m/s make the car
  // weave at 60. 0: fixed gains, as the paper.
  double schedule_above = 40;  // m/s (v0)
  double max_steer = 0.35;     // rad: the AV-21's for tests; the plugin takes the vehicle file's
  bool reduce_speed = true;    // false: hold
  // Slow down hard and early: a wall 8 m in is a tighter line than the racing line, and holding
  // 55 m/s on it in a banked turn spins the car (docs/results-resilience.md); 12 m/s² is the
  // braking the racing line's speed profile plans with.
  double fallback_speed = 25;  // m/s
  double decel = 12;           // m/s^2 to the fallback speed
  // Taking over slower than this (a car the manager stopped for want of a wall, handed back to
  // the wall follower once it sees one: ManagerParams::resume_on_wall), the speed it drives off
  // to, not the standstill it took over at; the curvature's limit below still holds.
  double restart_speed = 8;    // m/s
  double a_lat = 10;           // m/s^2: never faster than the wall's curvature allows at this
  double speed_gain = 0.5;
};

// A fitted wall as the followers see it: y(x) in the vehicle frame and where its points were
// (the offset line's extent; the paper's law reads only the polynomial).
struct WallView {
  std::vector<double> coefficients;  // y(x) = c0 + c1 x + ...
  bool valid = false;
  double x_min = 0, x_max = 0;       // extent of the fitted points, m
};

class WallFollower {
 public:
  explicit WallFollower(WallFollowerParams p = {}) : p_(p) {}
  const WallFollowerParams& params() const { return p_; }
  // Starts (or restarts) following at `speed`: what `hold` keeps and `reduce` starts from.
  void engage(double t, double speed);
  // The command at time t; an invalid wall gives a straight wheel and full brake.
  Command control(double t, const WallView& wall, double speed) const;
  // u_w alone (before the clamp), at the given speed (it sets the gains when scheduled).
  double steering(const WallView& wall, double speed = 0) const;

 private:
  WallFollowerParams p_;
  double t0_ = 0, v0_ = 0;
};

}  // namespace brickyard::control
