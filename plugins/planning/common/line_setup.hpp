#pragma once
// The racing line as both planners use it: kept inside the track's edges, with its speed profile
// (the simulator's track library serves as the map for now; docs/algorithms.md), as a RefLine for
// the road graph. Framework-free.
#include "road_graph.hpp"
#include "speed_profile.hpp"

#include "../../sim/common/pure_pursuit.hpp"
#include "../../sim/common/track.hpp"

#include <cstdint>

namespace brickyard::planning {

struct Reference {
  sim::RacingLine racing;      // points, s, curvature (smoothed), speed profile
  RefLine line;                // the same points as a Frenet frame
  std::vector<double> speed;   // per point
};

// The simulator's AV-21 (sim::VehicleParams) as speed-profile limits: drive force, power and drag
// per mass from its parameters; lateral grip 15 m/s² (μ g = 15.7 less a margin) and the brakes at
// the grip; downforce ignored. brickyard-plan's default car and the racing-line comparison's.
VehicleLimits av21_limits();

// `track` may be null (no world): the line is used as the file has it.
Reference make_reference(const sim::CenterLine& line, const sim::Track* track, double edge_margin,
                         const sim::SpeedLimits& limits);

// The track's edges across the line, for RoadGraph::build.
TrackRoom track_room(const sim::Track& track, const RefLine& line);

// Identifies what a graph file was built from — the racing line file's points, the edge margin
// and the graph parameters — so a mismatch is caught in configure, before anything runs. (The
// track itself is not in it: the world arrives as a message, after configure.)
std::uint64_t reference_digest(const sim::CenterLine& raceline, double edge_margin, const RoadGraphParams& p);

}  // namespace brickyard::planning
