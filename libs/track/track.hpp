#pragma once
// A track's geometry: a closed centre line with its widths and banking, and the Frenet frame
// along it (s along the line, d across, left positive). Framework-free: the car stack builds it
// from the map it is given, the simulator from its world, and unit tests directly.
#include "centre_line.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace brickyard::track {

// What a track is made of: a name, the centre line with widths, a bank angle per point.
struct TrackGeometry {
  std::string name;
  CenterLine line;
  std::vector<double> bank;  // rad per point, positive raises the left edge; empty: flat
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

  // Throws std::invalid_argument for fewer than 4 points, ragged columns or a zero-length segment.
  explicit Track(TrackGeometry geometry);

  const TrackGeometry& geometry() const { return geo_; }
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
  // Gradient of the road surface (dz/dx, dz/dy) in the map frame at f.
  Eigen::Vector2d road_gradient(const Frenet& f) const;

  int wrap(int i) const { int n = size(); return ((i % n) + n) % n; }
  double wrap_s(double s) const;

 private:
  double lerp(const std::vector<double>& v, int seg, double u) const;
  Frenet project_on(int seg, double x, double y) const;

  TrackGeometry geo_;
  std::vector<Segment> seg_;
  double length_ = 0;
  bool ccw_ = true;
};

}  // namespace brickyard::track
