#pragma once
// The racing line as both planners use it: kept inside the map's edges, with its speed profile
// (libs/motion), as a RefLine for the road graph. Framework-free.
#include "road_graph.hpp"

#include "motion/racing_line.hpp"
#include "motion/speed_profile.hpp"
#include "track/centre_line.hpp"
#include "track/track.hpp"

#include <cstdint>

namespace brickyard::planning {

using motion::VehicleLimits;

struct Reference {
  motion::RacingLine racing;   // points, s, curvature (smoothed), speed profile
  RefLine line;                // the same points as a Frenet frame
  std::vector<double> speed;   // per point
};

// `track` may be null (no map): the line is used as the file has it.
Reference make_reference(const track::CenterLine& line, const track::Track* track, double edge_margin,
                         const VehicleLimits& limits);

// The track's edges across the line, for RoadGraph::build.
TrackRoom track_room(const track::Track& track, const RefLine& line);

// Identifies what a graph file was built from — the racing line file's points, the edge margin
// and the graph parameters — so a mismatch is caught in configure, before anything runs. (The
// track itself is not in it: the map arrives as a message, after configure.)
std::uint64_t reference_digest(const track::CenterLine& raceline, double edge_margin, const RoadGraphParams& p);

}  // namespace brickyard::planning
