#pragma once
// example.my_plugin's algorithm, framework-free (no Brickyard types: unit tests call it directly):
// a path along the track's centre line from the car's place, at the speed its curvature and
// braking allow. A starting point for a planner: replace it with your own.
#include <cstddef>
#include <vector>

namespace my_plugin {

struct PathSettings {
  double ahead_m = 200;   // how far ahead of the car the path reaches
  double a_lat = 8;       // m/s^2, the lateral acceleration the speed allows in a turn
  double a_brake = 6;     // m/s^2, the deceleration the speed plans for before a turn
  double v_max = 45;      // m/s
};

struct PathPoint {
  double x = 0, y = 0, yaw = 0, curvature = 0, speed = 0, s = 0;
};

// The centre line of a closed track (the last point joins the first).
class CentreLinePath {
 public:
  // Throws std::invalid_argument with the reason for fewer than 3 points or x and y of different
  // sizes.
  CentreLinePath(std::vector<double> x, std::vector<double> y);

  // The path from the centre-line point nearest (car_x, car_y), `ahead_m` long, its arc length
  // from 0.
  std::vector<PathPoint> ahead_of(double car_x, double car_y, const PathSettings& settings) const;

 private:
  std::size_t nearest(double x, double y) const;
  std::size_t next(std::size_t i) const { return (i + 1) % x_.size(); }
  std::vector<double> x_, y_, curvature_;
};

}  // namespace my_plugin
