#pragma once
// control.wall_follower's parameters (plugin.cpp): the paper's law, the offset line's, and the car
// whose steering limit they keep. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "control/common/wall_follower.hpp"
#include "control/common/wall_line.hpp"
#include "vehicle_param.hpp"

#include <optional>
#include <string>

namespace brickyard::control {

// What the graph says: the law's parameters, and the car whose steering limit it keeps.
struct Settings {
  WallFollowerParams law;
  bool offset_line = false;         // the law: the paper's, or the offset line
  WallLineParams line;
  double r_steer = 200;             // offset_line: the LQR's steering cost (the car stack's, docs/control.md)
  double steer_margin = 0.8;        // offset_line: the line asks at most this share of the steering limit
  std::string vehicle = plugins::default_vehicle_file;
  std::optional<double> max_steer;  // NaN: the vehicle file's
};

inline ParamBinding<Settings> bindings() {
  using P = WallFollowerParams;
  ParamBinding<Settings> b;
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: its steering limit");
  b.bind_choice("side", {{"right", -1}, {"left", 1}}, &Settings::law, &P::side).doc("the wall followed");
  b.bind("w_theta", &Settings::law, &P::w_theta).range(-10, 10)
      .doc("rad of steer per unit of the wall's slope at the look-ahead");
  b.bind("w_d", &Settings::law, &P::w_d).in_unit("rad/m").range(-10, 10).doc("rad of steer per m of gap error");
  b.bind("gap", &Settings::law, &P::gap).in_unit("m").range(0, 100).doc("distance kept to the wall");
  b.bind("lookahead", &Settings::law, &P::lookahead).in_unit("m").range(0, 1000);
  b.bind("max_steer", &Settings::max_steer).in_unit("rad").range(0.01, 1.5).doc("steering limit; default: the vehicle file's");
  b.bind("schedule_above", &Settings::law, &P::schedule_above).in_unit("m/s").range(0, 200)
      .doc("above this speed the look-ahead grows and the gains shrink with speed as a pure pursuit's; 0: fixed");
  b.bind_choice("speed_policy", {{"reduce", true}, {"hold", false}}, &Settings::law, &P::reduce_speed)
      .doc("while following: slow to fallback_speed, or hold");
  b.bind("fallback_speed", &Settings::law, &P::fallback_speed).in_unit("m/s").range(0, 200);
  b.bind("decel", &Settings::law, &P::decel).in_unit("m/s^2").range(0.1, 100);
  b.bind("restart_speed", &Settings::law, &P::restart_speed).in_unit("m/s").range(0, 200)
      .doc("taking over slower than this (a car that had stopped), the speed it drives off to");
  b.bind("a_lat", &Settings::law, &P::a_lat).in_unit("m/s^2").range(0, 100).doc("the wall's bend caps the speed at sqrt(a_lat / curvature); 0: off");
  b.bind("speed_gain", &Settings::law, &P::speed_gain).range(0, 100);
  b.bind_choice("law", {{"paper", false}, {"offset_line", true}}, &Settings::offset_line)
      .doc("paper: u_w on the one wall wired to 'wall'; offset_line: the path tracker's LQR on a line placed by the nearer valid "
           "wall of 'wall_left' and 'wall_right' — the planner's path or the map's edge laid onto the wall, else a gap inside it "
           "(docs/algorithms.md)");
  using W = WallLineParams;
  b.bind("min_gap", &Settings::line, &W::min_gap).in_unit("m").range(0, 100)
      .doc("offset_line: never closer to the wall");
  b.bind("max_gap", &Settings::line, &W::max_gap).in_unit("m").range(0, 100)
      .doc("offset_line: the most kept; the gap is the car's distance to the wall when it takes it, within [min_gap, max_gap]");
  b.bind("hold_s", &Settings::line, &W::hold_s).in_unit("s").range(0, 60)
      .doc("offset_line: a lost wall's last line, carried by wheel speed and yaw rate, is followed this long while either wall may come back");
  b.bind("r_steer", &Settings::r_steer).in_unit("1/rad^2").range(1e-6, 1e6).doc("offset_line: the LQR's cost of the steering");
  b.bind("steer_margin", &Settings::steer_margin).range(0.1, 1).doc("offset_line: the line is never tighter than this share of the steering limit turns");
  b.not_above("min_gap", "max_gap");
  return b;
}

}  // namespace brickyard::control
