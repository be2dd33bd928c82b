#pragma once
// The simulated LiDAR sensor around the ray caster: where it sits and how its rows fan out (from
// the graph's metres and degrees), and frame by frame what its fault windows make of a scan (lost,
// the last frame again, or a fresh one with its range noise scaled). It counts what it returns and
// digests the points. Framework-free: the lidar node turns a fresh frame's points into a message.
#include "digest.hpp"
#include "faults.hpp"
#include "lidar.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::sim {

// The fault windows a LiDAR takes, over (range).
inline const std::vector<std::string> kLidarFaultTypes = {"noise", "frame_loss", "freeze", "dropout"};

// The field of view and the rows, in degrees as a graph gives them.
struct LidarRowsDeg {
  double h_fov_deg = 120;
  int rows = 32;
  double v_min_deg = -15, v_max_deg = 15;
  std::string row_spacing = "horizon";  // see row_elevations
  double horizon_exponent = 2.0;
  std::vector<double> row_angles_deg;  // explicit row elevations: override rows and spacing
};

// `spec` with its mount (m, base_link), orientation (roll, pitch, yaw in degrees), field of view and
// row elevations set from the graph's figures.
LidarSpec placed_spec(LidarSpec spec, const std::array<double, 3>& mount, const std::array<double, 3>& rpy_deg,
                      const LidarRowsDeg& rows);

class Scanner {
 public:
  Scanner() = default;  // to be assigned a configured one
  // The noise and frame losses draw from `rng` (its seed: the run's).
  Scanner(LidarSpec spec, FaultSchedule faults, Rng rng);

  // The world to scan, once it is known.
  void start(WorldSpec world);
  bool started() const { return caster_ != nullptr; }

  enum class Frame { lost, repeat, fresh };
  // The frame at time t, the car at world_from_body (its base_link at x, y), the other cars where
  // they are: lost (none this time), repeat (the last fresh frame again: a frozen sensor) or fresh
  // (its points in points()).
  Frame frame(double t, const Eigen::Isometry3d& world_from_body, double x, double y, const std::vector<CarBody>& cars = {});
  // A fresh frame's points, sensor frame; they may be moved out (the next scan reserves them again).
  PointBuffers& points() { return buf_; }

  const LidarSpec& spec() const { return spec_; }
  std::uint64_t frames() const { return frames_; }  // fresh frames
  std::uint64_t frames_lost() const { return lost_; }
  std::uint64_t rays() const { return rays_; }
  double points_per_frame() const { return frames_ ? static_cast<double>(points_) / frames_ : 0.0; }
  std::string digest() const { return digest_.hex(); }

 private:
  LidarSpec spec_;
  FaultSchedule faults_;
  Rng rng_;
  std::unique_ptr<Track> track_;
  std::unique_ptr<LidarCaster> caster_;
  PointBuffers buf_;
  Digest digest_;
  int hint_ = -1;
  std::uint64_t frames_ = 0, lost_ = 0, rays_ = 0, points_ = 0;
};

}  // namespace brickyard::sim
