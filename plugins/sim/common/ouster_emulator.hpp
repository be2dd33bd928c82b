#pragma once
// An Ouster sensor simulated from its metadata JSON, framework-free: one rotation cast against the
// track world pixel by pixel, in the directions the metadata gives each beam and column (its beam
// altitude and azimuth angles, the beam origin's offset from the lidar's, the lidar-to-sensor
// transform: the same table the driver turns ranges into points with, ouster_xyz.hpp), into the
// OusterFrame the packets carry. So the driver decoding the emulator's packets puts each point
// where the ray met the world, to the millimetre the packets hold. Why not the grid of sim.lidar:
// its rows share a column's azimuth, an Ouster's beams do not (an OS-1-32's are 4.2 degrees apart
// either way, staggered by pixel_shift_by_row), and a decoder applying the metadata's angles to a
// grid's ranges would misplace them by metres at a hundred.
// Columns are cast as the sensor measures them, across the rotation, each from the car's pose then
// (cast_columns): the frame carries the motion of the car while it turns, as a real one does, and
// its columns' stamps say when. docs/simulator.md, "An
// Ouster on its wire".
#include "drivers/common/ouster_frame.hpp"
#include "drivers/common/ouster_metadata.hpp"
#include "drivers/common/ouster_xyz.hpp"
#include "lidar.hpp"
#include "rng.hpp"
#include "track.hpp"

#include <Eigen/Geometry>

#include <cstdint>

namespace brickyard::sim {

struct OusterEmulatorParams {
  Eigen::Isometry3d body_from_sensor = Eigen::Isometry3d::Identity();  // the sensor's mount on the car
  double range_noise = 0.02;  // m, 1 sigma (an OS-1's precision is 1 to 3 cm)
  double dropout = 0;         // probability a return is lost
  double min_range = 0.5, max_range = 120;  // m: nearer or farther, the pixel reads 0 (no return)
  // Reflectivity of each surface (0 to 1, lambertian): the packets' reflectivity byte is 100 times
  // it times the cosine of incidence, as the sensor calibrates a lambertian target's to 0 to 100.
  double reflectivity_road = 0.15, reflectivity_wall = 0.6, reflectivity_pylon = 0.9, reflectivity_grass = 0.45;
};

class OusterEmulator {
 public:
  // The metadata must have parsed (parse_ouster_metadata); the track outlives the emulator.
  OusterEmulator(const Track& track, drivers::OusterMetadata metadata, OusterEmulatorParams params);

  // A rotation begun: `out` sized, cleared, its window's columns stamped across the rotation from
  // t0_ns (the sensor's clock), none cast yet.
  void begin(std::uint64_t t0_ns, std::uint16_t frame_id, drivers::OusterFrame& out) const;
  // The window's columns [first, last) (0: the window's first) cast from the car at
  // world_from_body (its base_link at x, y) and marked received: ranges, reflectivity, signal and
  // near-infrared per pixel. A sensor measures each column where the car is then: the plugin casts
  // a packet's columns as it sends it. Returns the rays cast.
  std::size_t cast_columns(const Eigen::Isometry3d& world_from_body, double x, double y, int first, int last, Rng& rng,
                           drivers::OusterFrame& out);
  // A whole rotation from one pose: begin, then every column.
  std::size_t scan(const Eigen::Isometry3d& world_from_body, double x, double y, std::uint64_t t0_ns, std::uint16_t frame_id,
                   Rng& rng, drivers::OusterFrame& out);
  // When column k of the window (0: its first) has been measured, ns after the rotation's start.
  double column_end_ns(int k) const { return (k + 1) * 1e9 / (metadata_.frames_per_second * static_cast<double>(metadata_.columns_per_frame)); }

  const drivers::OusterMetadata& metadata() const { return metadata_; }
  double rotation_s() const { return 1.0 / metadata_.frames_per_second; }

 private:
  void size_frame(drivers::OusterFrame& out) const;
  void cast_pixel(const Eigen::Isometry3d& world_from_sensor, int seg, int row, int column, Rng& rng, drivers::OusterFrame& out) const;
  double reflectivity(Surface s) const;

  const Track& track_;
  drivers::OusterMetadata metadata_;
  OusterEmulatorParams p_;
  drivers::OusterXyzTable table_;
  LidarCaster caster_;
  int hint_ = -1;
};

}  // namespace brickyard::sim
