#pragma once
// The racing line's parameters, shared by planning.racing_line and planning.road_graph so the two
// swap by the plugin's name: declared once, read once. Plugin-side (SDK), used by plugin.cpp files.
#include <brickyard/plugin.hpp>

#include "motion/racing_line.hpp"
#include "track/centre_line.hpp"

#include <string>

namespace brickyard::planning {

inline Manifest with_line_params(Manifest m) {
  const motion::VehicleLimits l;
  m.param(ParamSpec::string("raceline", "racelines/IMS.csv").doc("x_m,y_m file of the racing line"))
      .param(ParamSpec::number("v_max", l.v_max).in_unit("m/s").at_least(1))
      .param(ParamSpec::number("a_lat", l.a_lat).in_unit("m/s^2").at_least(0.5))
      .param(ParamSpec::number("a_accel", l.a_accel).in_unit("m/s^2").at_least(0.1))
      .param(ParamSpec::number("a_decel", l.a_decel).in_unit("m/s^2").at_least(0.1))
      .param(ParamSpec::number("edge_margin", 2.5).in_unit("m").at_least(0).doc("closest the racing line may come to a track edge"));
  return m;
}

struct LineParams {
  std::string file;          // the racing line file, found
  track::CenterLine line;    // its points
  motion::VehicleLimits limits;  // lateral and longitudinal each on its own (no ellipse)
  double edge_margin = 2.5;
};

// Throws BadInput naming the file when it cannot be read.
inline LineParams read_line_params(Context& ctx) {
  const Params& p = ctx.params();
  LineParams out;
  out.file = ctx.find_file(p.string("raceline"));
  try {
    out.line = track::load_xy_csv(out.file);
  } catch (const track::TrackFileError& e) {
    throw BadInput(std::string("raceline file ") + e.what());
  }
  if (out.line.x.size() < 3) throw BadInput("raceline file " + out.file + ": fewer than 3 points");
  out.limits = motion::independent_limits(p.number("v_max"), p.number("a_lat"), p.number("a_accel"), p.number("a_decel"));
  out.edge_margin = p.number("edge_margin");
  return out;
}

}  // namespace brickyard::planning
