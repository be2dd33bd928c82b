#include "line_setup.hpp"

#include "../../sim/common/vehicle_model.hpp"

#include <cstring>

namespace brickyard::planning {

VehicleLimits av21_limits() {
  const sim::VehicleParams p;
  VehicleLimits l;
  l.v_max = 90;
  l.a_lat = 15;
  l.a_accel = p.max_drive_force / p.mass;
  l.a_decel = 15;
  l.power = p.max_power / p.mass;
  l.drag = p.air_density * p.drag_area / (2 * p.mass);
  return l;
}

Reference make_reference(const sim::CenterLine& file_line, const sim::Track* track, double edge_margin,
                         const sim::SpeedLimits& limits) {
  const sim::CenterLine line = track ? sim::keep_inside(file_line, *track, edge_margin) : file_line;
  Reference r;
  r.racing = sim::make_racing_line(line, limits);
  r.line = RefLine(r.racing.x, r.racing.y, r.racing.kappa);
  r.speed = r.racing.speed;
  return r;
}

TrackRoom track_room(const sim::Track& track, const RefLine& line) {
  return [&track, &line](double s) {
    const Eigen::Vector2d p = line.point(s);
    const sim::Frenet f = track.project(p.x(), p.y());
    // The line's normal and the centre line's are near parallel: offsets add across.
    return std::make_pair(-track.width_right(f.seg, f.u) - f.d, track.width_left(f.seg, f.u) - f.d);
  };
}

std::uint64_t reference_digest(const sim::CenterLine& raceline, double edge_margin, const RoadGraphParams& p) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the bytes
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) { h ^= b[i]; h *= 1099511628211ull; }
  };
  mix(raceline.x.data(), raceline.x.size() * sizeof(double));
  mix(raceline.y.data(), raceline.y.size() * sizeof(double));
  const double params[] = {edge_margin,   p.layer_spacing, p.layer_spacing_turn, p.turn_curvature, p.lateral_step,
                           p.half_width,  p.edge_margin,   p.max_curvature,      p.max_edge_length};
  mix(params, sizeof(params));
  return h;
}

}  // namespace brickyard::planning
