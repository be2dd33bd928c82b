#pragma once
// The road-graph planner's adapter geometry, framework-free: obstacles from the vehicle frame into
// the map with the car's pose of their stamp, and a planned path as the poses (heading from the
// neighbours), curvature and arc length a Path message carries.
#include "road_graph_planner.hpp"

#include "math/estimate_history.hpp"

#include "track/track.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace brickyard::planning {

struct StampedPose {
  std::int64_t stamp_ns = 0;
  double x = 0, y = 0, yaw = 0;                // base_link in the map frame
  double position_sigma = 0, yaw_sigma = 0;    // the estimate's standard deviations, m and rad
};

// An obstacle at (ox, oy) in the vehicle frame of `at`, of size sx by sy, in the map frame; none
// when the result is not finite. A non-finite size is taken as the largest (5 m radius): the
// obstacle still blocks. The radius is half the larger side, within 0.1 to 5 m. Its variance: the
// pose's position's, its heading's times the range squared, and 0.1 m squared (-1 when the
// pose's spread is not a finite number).
std::optional<MapObstacle> obstacle_in_map(const StampedPose& at, double ox, double oy, double sx, double sy);

// Whether a detection at (x, y) (map frame) can stand in the car's way: its centre lies on the
// track at least `edge_band` inside both edges. A cluster at an edge or beyond is the wall, or a
// thing beside the track; the graph's nodes keep the car's side a margin from the edges, so
// nothing there needs avoiding — and a wall reported as obstacles must not close the road.
bool on_track(const track::Track& track, double x, double y, double edge_band, int hint = -1);

// How far inside the edges a detection at (ox, oy) in the vehicle frame of `at` must lie to be
// on the track: edge_band, and `sigmas` times the spread of its place in the map — the pose's
// position and its heading's, which grows with the range (a heading 0.003 rad off puts a wall
// 200 m ahead 0.6 m inside the edge: Hockenheim's far wall stripes were planned around). A
// spread that is not a finite number adds nothing: the detection is judged as placed.
double placement_band(const StampedPose& at, double ox, double oy, double edge_band, double sigmas);

// A detection as perception reports it: its centre and size in the vehicle frame, m.
struct Detection {
  double x = 0, y = 0, size_x = 0, size_y = 0;
};

// One list's detections, in the vehicle frame of `at`, into the map (obstacle_in_map): those that
// can stand in the car's way (on_track at their placement_band; every one when `track` is null)
// are appended to `seen`. Returns how many were off the track.
std::size_t place_detections(const StampedPose& at, const std::vector<Detection>& list, const track::Track* track, double edge_band,
                             double sigmas, std::vector<MapObstacle>& seen);

// The spreads an estimate carries beside its pose: standard deviations, m and rad.
struct PoseSpread {
  double position = 0, yaw = 0;
};
using PoseHistory = math::EstimateHistory<PoseSpread>;

// The spreads of an estimate whose covariance has these variances of x, y and yaw: the position's
// the larger of x's and y's (a negative variance counts as none).
PoseSpread pose_spread(double var_x, double var_y, double var_yaw);

// The car's pose at a stamp (math::EstimateHistory::at) with the spreads of the estimate nearer
// to it; none when the history is empty.
std::optional<StampedPose> pose_at(const PoseHistory& history, std::int64_t stamp_ns);

struct PathGeometry {
  std::vector<double> x, y, yaw, curvature, s;
  double max_offset = 0;  // the largest |d| from the racing line
};

// The planned points as a Path's poses: yaw toward the next point (the last toward itself from
// the one before), arc length from the first point.
PathGeometry path_geometry(const std::vector<PathSample>& points);

}  // namespace brickyard::planning
