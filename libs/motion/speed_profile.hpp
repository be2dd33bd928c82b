#pragma once
// Speed profiles by forward and backward passes (the quasi-steady-state method): the speed each
// point's curvature allows, then what the car can accelerate to and brake from. The ggv is an
// ellipse — the longitudinal budget shrinks as the lateral one is used — with aero drag slowing
// the car (helping the brakes, eating the engine's push) and an optional power limit.
// Framework-free.
#include <vector>

namespace brickyard::motion {

struct VehicleLimits {
  double v_max = 80;          // m/s
  double a_lat = 18;          // m/s², lateral
  double a_accel = 8;         // m/s², traction (before drag)
  double a_decel = 12;        // m/s², brakes (before drag)
  double drag = 0;            // 1/m: drag deceleration = drag · v² (ρ c_d A / 2m)
  double power = 0;           // m²/s³: engine power per mass; the push is at most power / v (0: none)
  bool ellipse = true;        // off: longitudinal and lateral budgets independent
  // The ggv's shape between its pure-lateral and pure-longitudinal limits: (a_x/A_x)^p + (a_y/A_y)^p
  // ≤ 1. 2 is the ellipse; below 2 the corners where the car brakes or pushes while it turns are
  // cut (1 a diamond): a margin for combined grip a car does not deliver, its extremes unchanged.
  double ellipse_exponent = 2;
};

// Speeds at the points of a line with curvature kappa[i] and ds[i] from point i to the next.
// closed: a loop (ds has one entry per point, the last back to the first; the passes go round
// twice so they settle across the start). Open: ds has n − 1 entries; v_start (≥ 0) is the speed
// at the first point and v_end (≥ 0) a cap at the last (the speed the line beyond allows).
// cap (when not null): a further speed limit per point.
std::vector<double> speed_profile(const std::vector<double>& ds, const std::vector<double>& kappa,
                                  const VehicleLimits& lim, bool closed, double v_start = -1, double v_end = -1,
                                  const std::vector<double>* cap = nullptr);

// Σ ds_i / mean(v_i, v_i+1): the time to drive the profile, s.
double profile_time(const std::vector<double>& ds, const std::vector<double>& v, bool closed);

// The lap time of a closed line, profile_time(ds, speed_profile(ds, kappa, lim, true), true), and
// its derivatives by each point's curvature (d_kappa) and each step (d_ds), by reverse
// accumulation through the passes: every speed is its curvature's cap, the braking limit from the
// next point or the push from the previous one, whichever is least, so the lap time's sensitivity
// flows back along those links. Where the ellipse's budget is near zero its slope is infinite; it
// is taken at a budget of at least 0.05 (a finite, conservative slope; the caller's line search
// judges by the true time).
double closed_lap_time_gradient(const std::vector<double>& ds, const std::vector<double>& kappa, const VehicleLimits& lim,
                                std::vector<double>& d_kappa, std::vector<double>& d_ds);

}  // namespace brickyard::motion
