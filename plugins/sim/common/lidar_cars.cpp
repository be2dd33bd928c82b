#include "lidar_cars.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace brickyard::sim {

namespace {

// The box's eight corners, world frame.
std::array<Eigen::Vector3d, 8> corners(const CarBody& car) {
  std::array<Eigen::Vector3d, 8> out;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d local((k & 1) ? car.front : -car.rear, (k & 2) ? car.half_width : -car.half_width,
                                (k & 4) ? car.top : car.bottom);
    out[k] = car.world_from_body * local;
  }
  return out;
}

// The columns whose azimuths (sensor frame) lie between the corners', a column's margin either
// side: up to two runs (a full-turn sensor sees a car across its back at both ends of its
// columns). Over a convex body seen from outside its azimuths run between two of its corners':
// measured from the azimuth of its first corner, they span less than a half turn; more, and the
// body stands around the sensor's axis, every column.
std::vector<std::pair<int, int>> columns_spanned(const std::array<Eigen::Vector3d, 8>& in_sensor, double h_fov, int cols) {
  if (cols == 1) return {{0, 0}};
  const double a0 = std::atan2(in_sensor[0].y(), in_sensor[0].x());
  double lo = 0, hi = 0;
  for (const auto& p : in_sensor) {
    const double d = std::remainder(std::atan2(p.y(), p.x()) - a0, 2 * M_PI);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  if (hi - lo >= M_PI) return {{0, cols - 1}};
  const double per = (cols - 1) / h_fov;  // columns per radian; column c looks at h_fov / 2 - c / per
  std::vector<std::pair<int, int>> runs;
  for (double turn : {-2 * M_PI, 0.0, 2 * M_PI}) {
    const double a_min = a0 + lo + turn, a_max = a0 + hi + turn;
    const int first = std::max(0, static_cast<int>(std::floor((h_fov / 2 - a_max) * per)) - 1);
    const int last = std::min(cols - 1, static_cast<int>(std::ceil((h_fov / 2 - a_min) * per)) + 1);
    if (first <= last) runs.emplace_back(first, last);
  }
  return runs;
}

}  // namespace

FrameCars::FrameCars(const std::vector<CarBody>& cars, const Eigen::Vector3d& o, const Eigen::Matrix3d& R, double h_fov,
                     double max_range, const std::vector<double>& col_c, const std::vector<double>& col_s,
                     const std::vector<double>& row_c, const std::vector<double>& row_s)
    : max_range_(max_range), col_c_(&col_c), col_s_(&col_s), row_c_(&row_c), row_s_(&row_s) {
  for (const CarBody& car : cars) {
    const double reach = std::hypot(std::max(car.front, car.rear), car.half_width, car.top);
    if ((car.world_from_body.translation() - o).norm() > max_range + reach) continue;
    std::array<Eigen::Vector3d, 8> in_sensor = corners(car);
    for (auto& p : in_sensor) p = R.transpose() * (p - o);
    const auto runs = columns_spanned(in_sensor, h_fov, static_cast<int>(col_c.size()));
    if (runs.empty()) continue;  // outside the field of view
    const Eigen::Matrix3d car_from_world = car.world_from_body.linear().transpose();
    Near n;
    n.o = car.world_from_body.inverse() * o;
    n.x = car_from_world * R.col(0);
    n.y = car_from_world * R.col(1);
    n.z = car_from_world * R.col(2);
    n.lo = Eigen::Vector3d(-car.rear, -car.half_width, car.bottom);
    n.hi = Eigen::Vector3d(car.front, car.half_width, car.top);
    n.columns = runs;
    near_.push_back(n);
  }
}

// The slab test in each car's frame: the ray enters the box where it has crossed the last of
// the three pairs of faces' entry planes before leaving by any; the face of that last entry is the
// one it meets.
CarHit FrameCars::first_hit(int r, int c, double world_t) const {
  CarHit best;
  double limit = world_t > 0 ? std::min(world_t, max_range_) : max_range_;
  for (const Near& n : near_) {
    if (!n.in(c)) continue;
    const Eigen::Vector3d u = n.x * (*col_c_)[c] + n.y * (*col_s_)[c];
    const Eigen::Vector3d v = (*row_c_)[r] * u + (*row_s_)[r] * n.z;
    double t_in = 0, t_out = limit;
    int face = -1;
    bool miss = false;
    for (int i = 0; i < 3 && !miss; ++i) {
      if (v[i] == 0) {
        miss = n.o[i] < n.lo[i] || n.o[i] > n.hi[i];
        continue;
      }
      double t1 = (n.lo[i] - n.o[i]) / v[i], t2 = (n.hi[i] - n.o[i]) / v[i];
      if (t1 > t2) std::swap(t1, t2);
      if (t1 > t_in) {
        t_in = t1;
        face = i;
      }
      t_out = std::min(t_out, t2);
      miss = t_in > t_out;
    }
    if (miss || face < 0 || t_in >= limit) continue;  // face < 0: the sensor is inside the box
    best = {t_in, std::abs(v[face])};
    limit = t_in;
  }
  return best;
}

}  // namespace brickyard::sim
