#pragma once
// The path tracker's parameters (libs/control), bound in one place for the two plugins that drive
// with it: control.path_tracker (the car stack) and sim.truth_follower (the simulator's
// ground-truth driver). Each plugin's defaults come from the TrackerParams in its settings; the
// car's facts come from its vehicle file (control::apply_vehicle), never from here.
#include <brickyard/plugin.hpp>

#include "control/path_tracker.hpp"
#include "control/vehicle_tracking.hpp"

#include <sstream>
#include <string>

namespace brickyard::plugins {

template <class S, class... M> void bind_tracker(ParamBinding<S>& b, M... path) {
  using T = control::TrackerParams;
  using Q = control::LateralLqrParams;
  b.bind_choice("steer_law", {{"pure_pursuit", control::SteerLaw::pure_pursuit}, {"lqr", control::SteerLaw::lqr}}, path..., &T::steer_law)
      .doc("pure_pursuit: the look-ahead point; lqr: the single-track model's curvature feedforward and LQR feedback (docs/control.md)");
  b.bind("lookahead_min", path..., &T::lookahead_min).in_unit("m").range(0.5, 1000).doc("pure_pursuit");
  b.bind("lookahead_time", path..., &T::lookahead_time).in_unit("s").range(0, 60).doc("pure_pursuit: look-ahead = this x speed, clamped");
  b.bind("lookahead_max", path..., &T::lookahead_max).in_unit("m").range(0.5, 1000).doc("pure_pursuit");
  b.bind("q_lateral", path..., &T::lqr, &Q::q_lateral).in_unit("1/m^2").range(0, 1e6).doc("lqr: cost of the lateral error");
  b.bind("q_heading", path..., &T::lqr, &Q::q_heading).in_unit("1/rad^2").range(0, 1e6).doc("lqr: cost of the heading error");
  b.bind("r_steer", path..., &T::lqr, &Q::r_steer).in_unit("1/rad^2").range(1e-6, 1e6).doc("lqr: cost of the steering");
  b.bind("r_steer_rate", path..., &T::lqr, &Q::r_steer_rate).in_unit("s^2/rad^2").range(0, 1e6)
      .doc("lqr: cost of the steering's rate: the law's bandwidth kept below what the delay allows");
  b.bind("command_latency", path..., &T::command_latency).in_unit("s").range(0, 0.5)
      .doc("lqr: a command's way to the steering actuator (manager, bus) and the estimate's age; the law plans over it and the vehicle file's steering delay");
  b.bind("max_lateral_error", path..., &T::lqr, &Q::max_lateral_error).in_unit("m").range(0.1, 20)
      .doc("lqr: the lateral error the feedback sees is clamped to this, so a car far off the path closes in at a bounded angle");
  b.bind("curvature_window", path..., &T::curvature_window).in_unit("m").range(2, 200)
      .doc("lqr: the path's curvature, for the feedforward, over this length");
  b.bind_choice("pedal_law", {{"proportional", control::PedalLaw::proportional}, {"feedforward", control::PedalLaw::feedforward}},
                path..., &T::pedal_law)
      .doc("proportional: pedal = speed_gain x error; feedforward: the profile's acceleration with the car's mass, drag and power, plus accel_gain x error");
  b.bind("speed_gain", path..., &T::speed_gain).range(0, 100).doc("proportional: pedal per m/s of speed error");
  b.bind("accel_gain", path..., &T::accel_gain).in_unit("1/s").range(0, 100).doc("feedforward: m/s^2 per m/s of speed error");
  b.bind("preview_time", path..., &T::preview_time).in_unit("s").range(0, 60).doc("path ahead the speed looks at");
  b.bind("decel", path..., &T::decel).in_unit("m/s^2").range(0.1, 100).doc("braking the speed plan assumes");
  b.not_above("lookahead_min", "lookahead_max");
}

// The tracker's parameters with the car's facts from its vehicle file (`file`, for the message):
// BadInput when the LQR would plan over more delay than it can (the file's steering delay and
// command_latency together).
inline control::TrackerParams tracker_for(control::TrackerParams t, const vehicle::Vehicle& car, const std::string& file) {
  control::apply_vehicle(t, car);
  if (t.steer_law == control::SteerLaw::lqr && t.steer_delay + t.command_latency > control::kMaxPlannedDelay + 1e-9) {
    std::ostringstream m;
    m << "parameter 'command_latency': " << t.command_latency << " s with the steering's " << t.steer_delay << " s delay ("
      << file << ") is more than the " << control::kMaxPlannedDelay << " s the lqr law plans over";
    throw BadInput(m.str());
  }
  return t;
}

}  // namespace brickyard::plugins
