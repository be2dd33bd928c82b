#pragma once
// Lateral control of a dynamic single-track (bicycle) model: the steering that follows a path at
// speed, as curvature feedforward plus LQR feedback on the path errors. Framework-free.
//
// Errors of the centre of gravity against the path (left positive): e_y, its rate, the heading
// error e_psi and its rate. Their linear dynamics at speed v (linear tyres, axle cornering
// stiffnesses Cf, Cr; Rajamani, Vehicle Dynamics and Control, 2.4):
//   d/dt [e_y, e_y', e_psi, e_psi'] = A(v) x + B delta + (a term in the path's curvature)
// The feedforward holds the steady turn of curvature kappa at speed v:
//   delta_ff = L kappa + K_v v^2 kappa,   K_v = m (lr / Cf - lf / Cr) / L   (understeer gradient)
// with the heading error it leaves, e_psi_ss = -lr kappa + lf m v^2 kappa / (Cr L), taken out of
// the feedback. The feedback gains K(v) solve the discrete LQR of (A(v), B) at the control period,
// tabulated over speed once at construction (the model changes with 1/v).
#include <array>
#include <vector>

namespace brickyard::control {

// The car as the lateral law sees it (from the vehicle description).
struct LateralModel {
  double mass = 0, yaw_inertia = 0;          // kg, kg m^2
  double lf = 0, lr = 0;                     // m, centre of gravity to the axles
  double cornering_front = 0, cornering_rear = 0;  // N/rad per axle
};

// The longest delay the law plans over: its state grows by a period of it, and no car races with
// more.
inline constexpr double kMaxPlannedDelay = 0.3;  // s

struct LateralLqrParams {
  // Costs: lateral error (1/m^2), its rate, heading error (1/rad^2), its rate; and the steering (1/rad^2).
  double q_lateral = 1.0, q_lateral_rate = 0.0, q_heading = 2.0, q_heading_rate = 0.0;
  double r_steer = 40.0;
  double r_steer_rate = 0.01;  // (rad/s)^-2: cost of the steering's rate
  double period = 0.01;  // s: the controller's step, the LQR's discretisation
  double delay = 0.0;    // s: from the command to the road wheels (rounded to periods), at most kMaxPlannedDelay
  // The lateral error the feedback sees is clamped to this: a car far off the path (at the start,
  // after an avoidance) closes in at a bounded angle instead of steering at the linear law's full
  // gain into a wall.
  double max_lateral_error = 1.5;  // m
  double v_min = 3, v_max = 100, v_step = 1;  // m/s: the gain table
};

// The steering that holds a steady turn of curvature kappa at speed v: L kappa + K_v v^2 kappa.
double steady_steer(const LateralModel& m, double kappa, double v);

struct PathErrors {
  double e_y = 0, e_y_rate = 0, e_psi = 0, e_psi_rate = 0;  // m, m/s, rad, rad/s; left positive
};

class LateralLqr {
 public:
  LateralLqr() = default;
  LateralLqr(LateralModel car, LateralLqrParams p);
  // The steering (road-wheel angle, left positive) for the errors on a path of curvature kappa at
  // speed v; unclamped. `past`: the feedback's own outputs of the last periods, newest first
  // (u(t-T), ...; memory() of them; missing ones count 0).
  double steer(const PathErrors& e, double kappa, double v, const std::vector<double>& past = {}) const;
  // How many past outputs the law plans with: the delay's periods, at least one (the rate's cost).
  int memory() const { return memory_; }
  // Feedforward and steady-state heading error alone (for tests and the report).
  double feedforward(double kappa, double v) const;
  double steady_heading_error(double kappa, double v) const;
  // The feedback gains at speed v (interpolated in the table): the four errors', then one per
  // past output.
  std::vector<double> gains(double v) const;

 private:
  LateralModel m_;
  LateralLqrParams p_;
  int memory_ = 1;
  std::vector<std::vector<double>> table_;
};

}  // namespace brickyard::control
