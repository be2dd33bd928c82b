#pragma once
// Other cars as a LiDAR sees them (issue 46): each a box over its footprint, posed as the car is
// (banked and pitched with it), met by a frame's rays where it is nearer than the world. Framework-
// free; the caster asks it ray by ray, for the columns a car can be in only, so a frame with no car
// near is cast as it was without (the same bits).
#include <Eigen/Geometry>

#include <utility>
#include <vector>

namespace brickyard::sim {

struct CarBody {
  Eigen::Isometry3d world_from_body = Eigen::Isometry3d::Identity();  // base_link (the rear axle, on the road)
  double front = 0, rear = 0, half_width = 0;                        // m, the footprint
  double bottom = 0.05, top = 1.0;                                    // m above base_link
};

// A car's hit on one ray: how far along it, and the cosine of its incidence on the face it meets.
struct CarHit {
  double t = 0;
  double cos_incidence = 1;
};

// The cars one frame's rays may meet. A ray is named by its row and column (the caster's tables
// of their cosines and sines, in the sensor's frame), so that the caster's two scans ask for the
// very same ray and get the same bits.
class FrameCars {
 public:
  FrameCars() = default;  // no car
  // The sensor at `o` with axes `R` (world frame); cars beyond max_range are left out.
  FrameCars(const std::vector<CarBody>& cars, const Eigen::Vector3d& o, const Eigen::Matrix3d& R, double h_fov,
            double max_range, const std::vector<double>& col_c, const std::vector<double>& col_s,
            const std::vector<double>& row_c, const std::vector<double>& row_s);

  // Whether a car can be in column c (a margin of a column either side).
  bool sees(int c) const {
    for (const Near& n : near_)
      if (n.in(c)) return true;
    return false;
  }
  // The first car the ray of row r, column c meets within max range, if nearer than `world_t`
  // (<= 0: the world returns nothing); t <= 0 when none.
  CarHit first_hit(int r, int c, double world_t) const;

 private:
  struct Near {
    Eigen::Vector3d o;     // the sensor in the car's frame
    Eigen::Vector3d x, y, z;  // the sensor's axes in the car's frame
    Eigen::Vector3d lo, hi;   // the box, car frame
    std::vector<std::pair<int, int>> columns;  // the runs of columns it may be in, first and last
    bool in(int c) const {
      for (const auto& [first, last] : columns)
        if (c >= first && c <= last) return true;
      return false;
    }
  };
  std::vector<Near> near_;
  double max_range_ = 0;
  const std::vector<double>*col_c_ = nullptr, *col_s_ = nullptr, *row_c_ = nullptr, *row_s_ = nullptr;
};

}  // namespace brickyard::sim
