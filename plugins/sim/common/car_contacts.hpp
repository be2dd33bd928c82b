#pragma once
// Cars against each other (issue 46): the plan-view rectangles of two cars (each its base_link
// pose and footprint), whether they touch and how far apart they are. The referee's bookkeeping
// of car contacts and gaps is made of these. Framework-free.
#include "referee.hpp"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <optional>
#include <vector>

namespace brickyard::sim {

struct CarBox {
  double x = 0, y = 0, yaw = 0;  // base_link (rear-axle centre), map frame
  Footprint fp;
};

// The rectangle's corners, counter-clockwise from the front left.
std::array<Eigen::Vector2d, 4> corners(const CarBox& c);

// Whether the two rectangles overlap (separating axes: none of their four edge normals parts them).
bool cars_touch(const CarBox& a, const CarBox& b);

// The least distance between the two rectangles, m; 0 when they touch.
double car_gap(const CarBox& a, const CarBox& b);

// Our car against the others, sample by sample: a contact counted when a car's rectangle first
// touches ours (not again while they stay touching), the least gap to any of them.
class CarContactBook {
 public:
  // Ours now and each other car's latest pose (none: not seen yet): the others whose contact with
  // ours begins now.
  std::vector<int> update(const CarBox& ours, const std::vector<std::optional<CarBox>>& others);
  int contacts() const { return contacts_; }
  double min_gap() const { return min_gap_; }  // m; +inf: no other car seen

 private:
  std::vector<bool> touching_;
  int contacts_ = 0;
  double min_gap_ = std::numeric_limits<double>::infinity();
};

}  // namespace brickyard::sim
