#pragma once
// The simulator's world: the shared track geometry (libs/track) plus what only the simulator
// knows — the walls and the pylons standing on the road. Framework-free: the world, vehicle,
// LiDAR and referee nodes each build one from the TrackWorld message, and unit tests directly.
// The car stack never sees this: it reads a map (libs/track through the TrackMap message).
#include "track/banking.hpp"
#include "track/centre_line.hpp"
#include "track/curvature.hpp"
#include "track/track.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace brickyard::sim {

// The shared geometry under the names the simulator has always used.
using track::BankSpec;
using track::bank_profile;
using track::CenterLine;
using track::counter_clockwise;
using track::cyclic_average;
using track::curvature_window;
using track::Frenet;
using track::load_centerline_csv;
using track::load_xy_csv;
using track::parse_centerline_csv;
using track::signed_curvature;
using track::TrackFileError;

struct Pylon {
  double s = 0, d = 0, radius = 0.2, height = 0.7;
  double x = 0, y = 0, z = 0;  // filled in by Track
};

struct Walls {
  bool left = false, right = false;
  double left_offset = 0, right_offset = 0;  // m beyond the edge
  double height = 1.2;                       // m above the road edge
};

struct WorldSpec : track::TrackGeometry {
  Walls walls;
  std::vector<Pylon> pylons;
};

class Track : public track::Track {
 public:
  explicit Track(WorldSpec spec);

  const WorldSpec& spec() const { return spec_; }
  // d of the wall lines (+inf / -inf where there is none).
  double wall_left_d(int seg, double u) const;
  double wall_right_d(int seg, double u) const;

 private:
  WorldSpec spec_;
};

}  // namespace brickyard::sim
