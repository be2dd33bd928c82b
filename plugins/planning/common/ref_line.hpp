#pragma once
// A closed reference line (the racing line) as a Frenet frame: arc length s, lateral offset d
// (left positive). Framework-free. Tangents and normals are blended between points, so an offset
// curve p(s) + d n(s) has no corners at the points even far from the line.
#include <Eigen/Core>

#include <vector>

namespace brickyard::planning {

class RefLine {
 public:
  RefLine() = default;
  // Points of a closed line (the last joins the first) and, per point, the curvature the line is
  // taken to have there (1/m, left turns positive; smoothed by the caller as it likes).
  RefLine(std::vector<double> x, std::vector<double> y, std::vector<double> kappa);

  int size() const { return static_cast<int>(x_.size()); }
  double length() const { return length_; }
  double wrap(double s) const;  // into [0, length)

  Eigen::Vector2d point(double s, double d = 0) const;
  Eigen::Vector2d normal(double s) const;  // unit, left
  double heading(double s) const;
  double kappa(double s) const;
  // A per-point quantity (one value per point, e.g. a speed profile) at s, linearly interpolated.
  double interpolate(const std::vector<double>& per_point, double s) const;
  // (s, d) of a map point; with a hint (the s of a nearby earlier query) the search is local,
  // falling back to all segments when the local answer lies at the window's edge.
  Eigen::Vector2d to_frenet(double x, double y, double hint_s = -1) const;

 private:
  int segment(double s, double* u) const;  // segment i (point i to i + 1) and 0..1 along it
  Eigen::Vector2d project_on(int i, double x, double y) const;  // (s, d) on segment i
  std::vector<double> x_, y_, kappa_, s_;
  std::vector<Eigen::Vector2d> n_;  // per point: the mean of the adjacent segments' normals
  double length_ = 0;
};

}  // namespace brickyard::planning
