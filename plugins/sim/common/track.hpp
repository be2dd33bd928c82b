#pragma once
// Track geometry for the simulator: a closed centre line with widths, banking, walls and pylons.
// Framework-free: the world, vehicle, LiDAR and referee nodes each build one from the TrackWorld
// message, and unit tests build one directly.
#include <Eigen/Core>

#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::sim {

// A centre-line file in the TUM racetrack-database format: `x_m,y_m,w_tr_right_m,w_tr_left_m`.
struct CenterLine {
  std::string source;
  std::vector<double> x, y, width_right, width_left;
};

// A problem with a track file; what() starts with "<file>:<line>:".
class TrackFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

CenterLine parse_centerline_csv(std::istream& in, const std::string& name);
CenterLine load_centerline_csv(const std::string& path);
// Racing lines carry x, y only (TUM `x_m,y_m`); widths are left at zero.
CenterLine load_xy_csv(const std::string& path);

struct Pylon {
  double s = 0, d = 0, radius = 0.2, height = 0.7;
  double x = 0, y = 0, z = 0;  // filled in by Track
};

struct Walls {
  bool left = false, right = false;
  double left_offset = 0, right_offset = 0;  // m beyond the edge
  double height = 1.2;                       // m above the road edge
};

struct WorldSpec {
  std::string name;
  CenterLine line;
  std::vector<double> bank;  // rad per point, positive raises the left edge; empty: flat
  Walls walls;
  std::vector<Pylon> pylons;
};

// Where a point is along the track: segment `seg` runs from point seg to seg + 1.
struct Frenet {
  int seg = 0;
  double u = 0;  // 0..1 along the segment (may leave the range slightly at a vertex)
  double s = 0;  // m along the centre line, in [0, length)
  double d = 0;  // m, left positive
};

class Track {
 public:
  struct Segment {
    Eigen::Vector2d p;  // start point
    Eigen::Vector2d t;  // unit tangent
    Eigen::Vector2d n;  // unit left normal
    double length = 0, s0 = 0;
  };

  explicit Track(WorldSpec spec);

  const WorldSpec& spec() const { return spec_; }
  const std::vector<Segment>& segments() const { return seg_; }
  int size() const { return static_cast<int>(seg_.size()); }
  double length() const { return length_; }
  bool counter_clockwise() const { return ccw_; }

  // Nearest point of the centre line. With a hint (the segment of a nearby earlier query) the
  // search is local; it falls back to all segments when the local answer is not trustworthy.
  Frenet project(double x, double y, int hint = -1) const;
  Frenet at(double s, double d) const;  // segment and u of an (s, d)
  Eigen::Vector2d position(const Frenet& f) const;
  double heading(const Frenet& f) const;

  // Per-point values interpolated along segment `seg` at `u`.
  double bank(int seg, double u) const;
  double width_left(int seg, double u) const;
  double width_right(int seg, double u) const;
  // Road surface height: the centre line is at z = 0, the cross-section is a straight line of
  // slope tan(bank), and the ground beyond an edge stays level at the edge's height.
  double road_z(const Frenet& f) const;
  // d of the wall lines (+inf / -inf where there is none).
  double wall_left_d(int seg, double u) const;
  double wall_right_d(int seg, double u) const;
  // Gradient of the road surface (dz/dx, dz/dy) in the map frame at f.
  Eigen::Vector2d road_gradient(const Frenet& f) const;

  int wrap(int i) const { int n = size(); return ((i % n) + n) % n; }
  double wrap_s(double s) const;

 private:
  double lerp(const std::vector<double>& v, int seg, double u) const;
  Frenet project_on(int seg, double x, double y) const;

  WorldSpec spec_;
  std::vector<Segment> seg_;
  double length_ = 0;
  bool ccw_ = true;
};

// Whether the closed line runs counter-clockwise (positive shoelace area): its outside is then on
// the right.
bool counter_clockwise(const CenterLine& line);

// Signed curvature (1/m, left turns positive) per point, averaged over `smooth_m` of track: the
// Menger (three-point) curvature of each point, then cyclic_average over curvature_window points
// each side.
std::vector<double> signed_curvature(const CenterLine& line, double smooth_m);

// The half width, in points, of signed_curvature's average: smooth_m / 2 in mean steps of the
// closed line, rounded (0 for smooth_m <= 0).
int curvature_window(const CenterLine& line, double smooth_m);

// The cyclic moving average of v over the 2·half + 1 points around each. A symmetric linear map,
// so it is its own adjoint: derivatives by the averaged values become derivatives by the raw
// ones through the same function.
std::vector<double> cyclic_average(const std::vector<double>& v, int half);

struct BankSpec {
  std::string mode = "none";          // none | constant | curvature | segments
  double degrees = 0;                 // constant and curvature modes
  double curvature_threshold = 1e-3;  // 1/m: a point is in a turn above this (curvature mode)
  double transition_m = 100;          // m over which the bank ramps in and out
  struct Range { double s0, s1, degrees; };
  std::vector<Range> segments;        // segments mode
};

// Bank angle per point (rad, positive raises the left edge). Positive degrees raise the outside:
// of each turn in curvature mode, of the loop (the right side of a counter-clockwise loop) in the
// constant and segments modes.
std::vector<double> bank_profile(const CenterLine& line, const BankSpec& spec);

}  // namespace brickyard::sim
