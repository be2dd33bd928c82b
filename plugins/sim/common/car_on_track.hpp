#pragma once
// The simulated car on the world's road: the vehicle model placed on the track, stepped on the
// road's slope under it, and its ground truth at base_link (the rear-axle centre) with the road's
// height, pitch and roll there and the centre line's s and d. Framework-free: the vehicle node
// feeds it commands and publishes its truth.
#include "command_watchdog.hpp"
#include "track.hpp"
#include "vehicle_model.hpp"

#include <string>
#include <vector>

namespace brickyard::sim {

// Ground truth at base_link: map-frame pose on the road, body-frame velocity and acceleration.
struct BaseLinkTruth {
  double x = 0, y = 0, z = 0, yaw = 0, pitch = 0, roll = 0;
  double vx = 0, vy = 0, yaw_rate = 0, ax = 0, ay = 0, steer = 0;
  double s = 0, d = 0;  // on the centre line
};

// Why a car of this half width placed at (s, d) would stand off the road (its side beyond an
// edge), in words; empty when it stands on it.
std::string off_the_road(const Track& track, double s, double d, double half_width);

// Another car's start on the centre line.
struct StartPlace {
  double s = 0, d = 0;
};
// Why a car starting at `ours` would stand inside another of the same shape starting at `other`
// (footprints `front` ahead of and `rear` behind base_link along s, `half_width` either side; s
// apart the short way round a loop of `length` m when > 0), in words; empty when clear.
std::string start_inside(const StartPlace& ours, const StartPlace& other, double front, double rear, double half_width, double length);
// The starts of a JSON array of [s, d] pairs. Throws std::invalid_argument naming the JSON pointer
// at fault.
std::vector<StartPlace> parse_starts(const std::string& json_text);

class CarOnTrack {
 public:
  explicit CarOnTrack(VehicleParams p) : model_(std::move(p)) {}

  // The car at s along the centre line, d to its left, heading along the track at `speed` (its
  // base_link there). The track outlives the car's use of it.
  void place(const Track& track, double s, double d, double speed);
  bool placed() const { return track_ != nullptr; }
  // One integration step; throws std::runtime_error when the state is no longer finite.
  void step(double dt, const Command& c);
  // The truth now (it also keeps the car's segment on the track for the next step).
  BaseLinkTruth truth();

  const CarState& state() const { return model_.state(); }

 private:
  VehicleModel model_;
  const Track* track_ = nullptr;
  int hint_ = -1;  // the centre-line segment base_link was last on
};

// The command watchdog over one step (see CommandWatchdog::apply), with the warning to log when it
// took over from the stack or handed back to it (empty otherwise).
struct WatchedCommand {
  Command command;
  std::string warning;
};
WatchedCommand watch_command(CommandWatchdog& watchdog, double now, bool fresh, const Command& newest);

}  // namespace brickyard::sim
