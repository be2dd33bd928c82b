#pragma once
// Synthetic scenes for the mapping tests: a walled yard with boxes (every direction told), a
// corridor of two smooth walls (nothing along it), and planar poses.
#include "mapping/common/covariances.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace brickyard::mapping::scenes {

// A walled yard: the ground, a wall along each side, one across the end, and five boxes, sampled
// every `step` m with `noise` m of range noise (one seed per sampling).
inline Points yard(double step, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, static_cast<float>(noise));
  Points pts;
  auto add = [&](double x, double y, double z) { pts.emplace_back(x + n(rng), y + n(rng), z + n(rng)); };
  for (double x = -20; x <= 20; x += step)
    for (double y = -6; y <= 6; y += step) add(x, y, 0.002 * x * x);  // a gentle bowl, not flat
  for (double x = -20; x <= 20; x += step)
    for (double z = 0; z <= 1.2; z += step) add(x, -6, z), add(x, 6, z);
  for (double y = -6; y <= 6; y += step)
    for (double z = 0; z <= 1.2; z += step) add(20, y, z);
  const double boxes[5][2] = {{-12, 2}, {-4, -3}, {3, 1}, {9, -2}, {15, 3.5}};
  for (const auto& b : boxes)
    for (double u = 0; u <= 1.0; u += step)
      for (double z = 0; z <= 1.0; z += step) {
        add(b[0] + u, b[1], z), add(b[0] + u, b[1] + 1, z);
        add(b[0], b[1] + u, z), add(b[0] + 1, b[1] + u, z);
      }
  return pts;
}

inline Points moved(const Points& pts, const Eigen::Isometry3d& T) {
  Points out;
  for (const auto& p : pts) out.push_back((T * p.cast<double>()).cast<float>());
  return out;
}

// A corridor: flat ground and two smooth parallel walls along x, nothing across: a scan of it
// says where the car is across and how it is turned, not how far along.
inline Points corridor(double step, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 0.01f);
  Points pts;
  for (double x = -30; x <= 30; x += step) {
    for (double y = -6; y <= 6; y += step) pts.emplace_back(x + n(rng), y + n(rng), n(rng));
    for (double z = 0; z <= 1.2; z += step) pts.emplace_back(x + n(rng), -6 + n(rng), z), pts.emplace_back(x + n(rng), 6 + n(rng), z);
  }
  return pts;
}

inline Eigen::Isometry3d planar(double x, double y, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(x, y, 0));
  T.rotate(Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()));
  return T;
}

inline double yaw_of(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

}  // namespace brickyard::mapping::scenes
