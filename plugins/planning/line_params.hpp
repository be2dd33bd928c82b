#pragma once
// The racing line's parameters, shared by planning.racing_line and planning.road_graph so the two
// swap by the plugin's name: bound once, loaded once. Plugin-side (SDK), used by plugin.cpp files.
#include <brickyard/plugin.hpp>

#include "planning/common/line_setup.hpp"
#include "motion/racing_line.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/centre_line.hpp"
#include "vehicle/vehicle.hpp"

#include <limits>
#include <optional>
#include <string>

namespace brickyard::planning {

// What the graph says about the line.
struct LineSettings {
  std::string raceline = "plan";
  std::optional<double> v_max;   // graph limits: 80 m/s when unset; vehicle limits: a cap (unset: the car's)
  double a_lat = 18, a_accel = 8, a_decel = 12;  // graph limits, each on its own
  bool vehicle_limits = true;    // the vehicle file's envelope (ellipse, drag, power)
  double grip_use = 0.93;        // vehicle limits: the share of the lateral grip planned with
  double ellipse_exponent = 2;   // vehicle limits: the ggv's shape the speeds are planned with (2: the ellipse)
  double curvature_smooth_m = 10;
  double edge_margin = 2.5;
};

// Binds raceline, v_max, a_lat, a_accel, a_decel, profile_limits, grip_use, curvature_smooth_m and
// edge_margin to the LineSettings at `path`.
template <class S, class... M> void bind_line(ParamBinding<S>& b, M... path) {
  using L = LineSettings;
  b.bind("raceline", path..., &L::raceline)
      .doc("x_m,y_m file of the racing line, or plan: the line brickyard-plan line computes, planned for the map's track and the car at start");
  b.bind("v_max", path..., &L::v_max).in_unit("m/s").range(1, 200)
      .doc("top speed: profile_limits graph 80 when unset; vehicle a cap below the car's (unset: the car's)");
  b.bind("a_lat", path..., &L::a_lat).in_unit("m/s^2").range(0.5, 100).doc("profile_limits graph");
  b.bind("a_accel", path..., &L::a_accel).in_unit("m/s^2").range(0.1, 100).doc("profile_limits graph");
  b.bind("a_decel", path..., &L::a_decel).in_unit("m/s^2").range(0.1, 100).doc("profile_limits graph");
  b.bind_choice("profile_limits", {{"graph", false}, {"vehicle", true}}, path..., &L::vehicle_limits)
      .doc("the speed profile's limits: vehicle (the vehicle file's envelope: the ellipse, drag, power) or graph (v_max, a_lat, a_accel, a_decel, each on its own)");
  b.bind("grip_use", path..., &L::grip_use).range(0.1, 1)
      .doc("profile_limits vehicle: the share of the file's lateral acceleration planned with (a margin for transients)");
  b.bind("ellipse_exponent", path..., &L::ellipse_exponent).range(1, 2)
      .doc("profile_limits vehicle: the speeds' ggv, (a_x/A_x)^p + (a_y/A_y)^p <= 1: 2 the ellipse, less cuts the corners where the car brakes or pushes while it turns");
  b.bind("curvature_smooth_m", path..., &L::curvature_smooth_m).in_unit("m").range(0, 200)
      .doc("the profile reads the line's curvature averaged over this");
  b.bind("edge_margin", path..., &L::edge_margin).in_unit("m").range(0, 100)
      .doc("closest the racing line may come to a track edge: the planned line's margin, or how far inside a file's points are kept");
}

// The settings with the file read and the car's limits applied. Throws BadInput naming the file
// when it cannot be read. `files` finds it: the Context in configure, the CheckView at validation.
template <class Files> LineSource load_line(const Files& files, const LineSettings& s, const vehicle::Vehicle& car) {
  LineSource out;
  out.plan = s.raceline == "plan";
  if (!out.plan) {
    const std::string file = files.find_file(s.raceline);
    try {
      out.file_line = track::load_xy_csv(file);
    } catch (const track::TrackFileError& e) {
      throw BadInput(std::string("raceline file ") + e.what());
    }
    if (out.file_line.x.size() < 3) throw BadInput("raceline file " + file + ": fewer than 3 points");
    out.file_line.source = file;
  }
  out.plan_limits = motion::vehicle_limits(car);  // as brickyard-plan line plans
  if (s.vehicle_limits) {
    out.limits = out.plan_limits;
    out.limits.a_lat *= s.grip_use;
    out.limits.ellipse_exponent = s.ellipse_exponent;
    if (s.v_max) out.limits.v_max = std::min(out.limits.v_max, *s.v_max);
  } else {
    out.limits = motion::independent_limits(s.v_max.value_or(80), s.a_lat, s.a_accel, s.a_decel);
  }
  out.edge_margin = s.edge_margin;
  out.curvature_smooth_m = s.curvature_smooth_m;
  return out;
}

}  // namespace brickyard::planning
