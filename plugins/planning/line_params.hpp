#pragma once
// The racing line's parameters, shared by planning.racing_line and planning.road_graph so the two
// swap by the plugin's name: bound once, loaded once. Plugin-side (SDK), used by plugin.cpp files.
#include <brickyard/plugin.hpp>

#include "motion/racing_line.hpp"
#include "track/centre_line.hpp"

#include <string>

namespace brickyard::planning {

// What the graph says about the line.
struct LineSettings {
  std::string raceline = "racelines/IMS.csv";
  motion::VehicleLimits limits;  // v_max and the accelerations; lateral and longitudinal apart
  double edge_margin = 2.5;
};

// What the planners use: the settings with the file read.
struct LineParams {
  std::string file;          // the racing line file, found
  track::CenterLine line;    // its points
  motion::VehicleLimits limits;  // lateral and longitudinal each on its own (no ellipse)
  double edge_margin = 2.5;
};

// Binds raceline, v_max, a_lat, a_accel, a_decel and edge_margin to the LineSettings at `path`.
template <class S, class... M> void bind_line(ParamBinding<S>& b, M... path) {
  using L = LineSettings;
  using V = motion::VehicleLimits;
  b.bind("raceline", path..., &L::raceline).doc("x_m,y_m file of the racing line");
  b.bind("v_max", path..., &L::limits, &V::v_max).in_unit("m/s").at_least(1);
  b.bind("a_lat", path..., &L::limits, &V::a_lat).in_unit("m/s^2").at_least(0.5);
  b.bind("a_accel", path..., &L::limits, &V::a_accel).in_unit("m/s^2").at_least(0.1);
  b.bind("a_decel", path..., &L::limits, &V::a_decel).in_unit("m/s^2").at_least(0.1);
  b.bind("edge_margin", path..., &L::edge_margin).in_unit("m").at_least(0).doc("closest the racing line may come to a track edge");
}

// Throws BadInput naming the file when it cannot be read.
inline LineParams load_line(Context& ctx, const LineSettings& s) {
  LineParams out;
  out.file = ctx.find_file(s.raceline);
  try {
    out.line = track::load_xy_csv(out.file);
  } catch (const track::TrackFileError& e) {
    throw BadInput(std::string("raceline file ") + e.what());
  }
  if (out.line.x.size() < 3) throw BadInput("raceline file " + out.file + ": fewer than 3 points");
  out.limits = motion::independent_limits(s.limits.v_max, s.limits.a_lat, s.limits.a_accel, s.limits.a_decel);
  out.edge_margin = s.edge_margin;
  return out;
}

}  // namespace brickyard::planning
