#pragma once
// The racing line as both planners use it: kept inside the map's edges, with its speed profile
// (libs/motion), as a RefLine for the road graph. Framework-free.
#include "road_graph.hpp"

#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "track/centre_line.hpp"
#include "track/track.hpp"

#include <cstdint>
#include <stdexcept>

namespace brickyard::planning {

using motion::VehicleLimits;

struct Reference {
  motion::RacingLine racing;   // points, s, curvature (smoothed), speed profile
  RefLine line;                // the same points as a Frenet frame
  std::vector<double> speed;   // per point
};

// Where the racing line comes from and how it is driven.
struct LineSource {
  bool plan = false;             // planned for the map's track (line_plan.hpp); else `file_line`
  track::CenterLine file_line;   // a racing line file's points
  double edge_margin = 2.5;      // m: the planned line's margin from the edges, or how far inside
                                 // them a file's points are kept (motion::keep_inside)
  VehicleLimits plan_limits;     // plan: the car's envelope the line is refined under
  VehicleLimits limits;          // the speed profile's
  double curvature_smooth_m = 30;  // the profile reads the curvature averaged over this
};

// A racing line file whose points leave the track: what() names the first point and how far
// beyond which edge it lies.
struct LineLeavesTrack : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The line's points: planned for the track, or the file's kept inside its edges. `track` may be
// null (no map): the file's points as they are; a planned line needs the track
// (std::invalid_argument). A file's line with a point beyond an edge throws LineLeavesTrack:
// pulling such a point in (keep_inside) would kink the line where it is wrong, and the car
// followed it into the wall.
track::CenterLine line_points(const LineSource& src, const track::Track* track);

Reference make_reference(const LineSource& src, const track::Track* track);
// A file's line with a 30 m curvature average (brickyard-plan graph, the bench).
Reference make_reference(const track::CenterLine& line, const track::Track* track, double edge_margin,
                         const VehicleLimits& limits);

// The lap the line's speed profile plans, s (motion::profile_time over the closed line): what a
// driven lap is measured against.
double planned_lap(const motion::RacingLine& r);

// The track's edges across the line, for RoadGraph::build.
TrackRoom track_room(const track::Track& track, const RefLine& line);

// Identifies what a graph file was built from — the racing line file's points, the edge margin
// and the graph parameters — so a mismatch is caught in configure, before anything runs. (The
// track itself is not in it: the map arrives as a message, after configure.)
std::uint64_t reference_digest(const track::CenterLine& raceline, double edge_margin, const RoadGraphParams& p);

}  // namespace brickyard::planning
