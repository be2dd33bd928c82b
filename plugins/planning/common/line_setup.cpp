#include "line_setup.hpp"

#include "line_plan.hpp"
#include "math/fnv1a.hpp"

#include <cmath>
#include <stdexcept>

namespace brickyard::planning {

track::CenterLine line_points(const LineSource& src, const track::Track* track) {
  if (src.plan) {
    if (!track) throw std::invalid_argument("a planned racing line needs the track (wire the map)");
    return plan_line(track->geometry().line, src.plan_limits, src.edge_margin);
  }
  if (!track) return src.file_line;
  if (const std::string where = motion::leaves_track(src.file_line, *track); !where.empty())
    throw LineLeavesTrack("the line leaves the track: " + where);
  return motion::keep_inside(src.file_line, *track, src.edge_margin);
}

Reference make_reference(const LineSource& src, const track::Track* track) {
  Reference r;
  r.racing = motion::make_racing_line(line_points(src, track), src.limits, src.curvature_smooth_m);
  r.line = RefLine(r.racing.x, r.racing.y, r.racing.kappa);
  r.speed = r.racing.speed;
  return r;
}

Reference make_reference(const track::CenterLine& file_line, const track::Track* track, double edge_margin,
                         const VehicleLimits& limits) {
  LineSource src;
  src.file_line = file_line;
  src.edge_margin = edge_margin;
  src.limits = limits;
  return make_reference(src, track);
}

double planned_lap(const motion::RacingLine& r) {
  const std::size_t n = r.x.size();
  std::vector<double> ds(n);
  for (std::size_t i = 0; i < n; ++i) ds[i] = std::hypot(r.x[(i + 1) % n] - r.x[i], r.y[(i + 1) % n] - r.y[i]);
  return motion::profile_time(ds, r.speed, true);
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
