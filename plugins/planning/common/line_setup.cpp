#include "line_setup.hpp"

#include "math/fnv1a.hpp"

namespace brickyard::planning {

Reference make_reference(const track::CenterLine& file_line, const track::Track* track, double edge_margin,
                         const VehicleLimits& limits) {
  const track::CenterLine line = track ? motion::keep_inside(file_line, *track, edge_margin) : file_line;
  Reference r;
  r.racing = motion::make_racing_line(line, limits);
  r.line = RefLine(r.racing.x, r.racing.y, r.racing.kappa);
  r.speed = r.racing.speed;
  return r;
}

TrackRoom track_room(const track::Track& track, const RefLine& line) {
  return [&track, &line](double s) {
    const Eigen::Vector2d p = line.point(s);
    const track::Frenet f = track.project(p.x(), p.y());
    // The line's normal and the centre line's are near parallel: offsets add across.
    return std::make_pair(-track.width_right(f.seg, f.u) - f.d, track.width_left(f.seg, f.u) - f.d);
  };
}

std::uint64_t reference_digest(const track::CenterLine& raceline, double edge_margin, const RoadGraphParams& p) {
  math::Fnv1a h;
  h.add(raceline.x.data(), raceline.x.size() * sizeof(double));
  h.add(raceline.y.data(), raceline.y.size() * sizeof(double));
  const double params[] = {edge_margin,   p.layer_spacing, p.layer_spacing_turn, p.turn_curvature, p.lateral_step,
                           p.half_width,  p.edge_margin,   p.max_curvature,      p.max_edge_length};
  h.add(params, sizeof(params));
  return h.value();
}

}  // namespace brickyard::planning
