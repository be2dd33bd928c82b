#pragma once
// The line the stop along the last path follows when the interface has the track's map: the path,
// moved away from the nearer edge as the stop goes on. Why: after the trip nothing corrects the
// dead reckoning, and its heading error (the estimate's at the trip, the gyro's drift since)
// carries the car off its line by that angle times the distance covered. The racing line runs
// edge_margin from the edges through a turn's exit; a stop of 150 m with half a degree of heading
// error ends 1.3 m off, on the wall (docs/vehicle-interface.md, "Room to the edges").
// So the line keeps the car's centre at least `room` from each edge, room growing from what the
// path has at the trip by tan(heading_doubt) per metre covered (after a gentle onset); where the track is narrower than
// twice that, the line runs midway between its edges. The move is smoothed along the line, and
// kept only as far as the line stays drivable at the stop's pace: squeezing a chicane's line into
// the middle of a narrow track tightens its turns past the grip (Monza's first chicane met the
// wall that way), so where the moved line would ask more lateral grip than the path did there, or
// than the stop's braking leaves, the move is halved, then halved again, then dropped.
// It knows no obstacles: the interface has no perception; a car stopped by it is race control's.
// Framework-free.
#include "control/path_tracker.hpp"
#include "track/track.hpp"

#include <vector>

namespace brickyard::vehicle_interface {

struct StopLineParams {
  double edge_room_m = 2.5;        // the room at the trip (less where the path has less there)
  double heading_doubt_deg = 1.0;  // the heading error the room grows for, per metre covered
  double smoothing_m = 30;         // the length the move is averaged over along the line
  // The room's growth starts gently, reaching its full rate this far from the trip (a kink there
  // would be a turn of the wheel at full speed, on a line the grip may already hold at its limit):
  // the room is tan(heading_doubt) x onset_m / 2 (0.52 m at 1 degree) short of the doubt's drift
  // from there on.
  double onset_m = 60;
};

// The stop's pace, to judge a line drivable by: its speed at the trip, the deceleration it brakes
// at least at (it also meets the path's own speeds ahead), the tyres' grip (m/s^2).
struct StopPace {
  double speed = 0, decel = 0, grip = 0;
};

// `path` with the points from `from` on moved as above (those before it unchanged); a loop (a
// racing line) comes back beginning at `from`, and goes round past its end. A point the track's
// edges do not bracket (the path off the map) is not moved for room (its neighbours' smoothing may
// move it a little). A pace with no grip (0) bounds nothing by it.
std::vector<control::PathPoint> stop_line(const std::vector<control::PathPoint>& path, std::size_t from,
                                          const track::Track& track, const StopLineParams& p, const StopPace& pace);

// The curvature (1/m, left positive) at point i: the project's (track::menger_curvature) of the
// points `half` m either side of it; 0 near an end.
double curvature_at(const std::vector<control::PathPoint>& line, std::size_t i, double half);

}  // namespace brickyard::vehicle_interface
