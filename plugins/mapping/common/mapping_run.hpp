#pragma once
// mapping.scan_mapper's work over a drive, framework-free: the pose estimates (each frame's guess
// and prior, at its stamp), gravity's level from the IMU, each frame registered and joined to the
// map (ScanMapper) with the roll, pitch and height the last frame found, the road surface from
// the LiDARs' raw returns, the summary's statistics, and the map and the track written at the
// end. The plugin converts the messages and publishes.
#include "gravity_tilt.hpp"
#include "road_surface.hpp"
#include "scan_mapper.hpp"
#include "track_extraction.hpp"

#include "math/estimate_history.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::mapping {

struct MappingRunParams {
  ScanMapperParams mapper;
  RoadSurfaceParams surface;
  TrackExtractionParams extraction;
  double max_estimate_age = 0.1;  // s: a frame with no estimate this near its stamp is left out
  bool level_on_ground = true;    // frames join the map with their ground's roll, pitch and height
  double level_window = 4.0, level_time = 5.0;  // s: gravity's level (GravityTilt) and how fast it is turned out
};

// What an estimate carries beside its pose.
struct EstimateExtras {
  double speed = 0, yaw_rate = 0;
  std::array<double, 9> covariance{};  // row-major over (x, y, yaw)
  std::uint8_t status = 0;             // 0 NORMAL (its GNSS's), 1 WARNING, 2 EMERGENCY
};

// The pose found for a frame, as the published estimate carries it, and the pose the frame joined
// the map on.
struct FramePose {
  std::int64_t stamp_ns = 0;
  double x = 0, y = 0, yaw = 0, speed = 0, yaw_rate = 0;  // speed and yaw rate: the estimate's
  std::array<double, 9> covariance{};                     // row-major over (x, y, yaw)
  std::uint8_t update_case = 0;                           // 2: registered, 0: the guess
  std::uint8_t status = 0;                                // the estimate's
  Eigen::Isometry3d map_pose = Eigen::Isometry3d::Identity();
};

// A file written at the end: the line to log, or (ok false) what went wrong.
struct FileWritten {
  bool ok = false;
  std::string message;
};

// The track written at the end, with the summary's figures.
struct TrackWritten : FileWritten {
  double points = 0;       // the track's points
  double sides_found = 0;  // share of the stations' sides whose edge was found
  std::string error;       // what went wrong (the `track_error` metric)
};

// A place a file cannot be written to, said now and not after the laps: the problem naming the
// parameter, or empty (an empty path, or one that can be written).
std::string unwritable(const std::string& param, const std::string& path);

class MappingRun {
 public:
  // `road_surface`: the LiDARs' raw returns are gathered into the road surface (a track is
  // extracted at the end).
  MappingRun(const MappingRunParams& p, bool road_surface);

  void estimate(std::int64_t stamp_ns, const math::PlanarPose& pose, const EstimateExtras& extras);
  // An IMU sample (vehicle frame, m/s^2 and rad/s): gravity's level, with the newest estimate's
  // speed (both come at 125 Hz). Before any estimate: not taken.
  void imu(std::int64_t stamp_ns, double accel_x, double accel_y, double yaw_rate);
  // A cloud that could not be read: counted; true for the first (said once).
  bool malformed() { return malformed_++ == 0; }
  // One frame (vehicle frame) of `points`, the first `ground` of them its ground: registered onto
  // the map from the estimate at its stamp (interpolated, its spreads and status the nearer's)
  // and joined to it. None, counted, without an estimate within max_estimate_age or with one
  // that is not finite. `imu_wired`: gravity levels the frames.
  std::optional<FramePose> frame(std::int64_t stamp_ns, const Points& points, std::size_t ground, bool imu_wired);
  // One LiDAR's raw returns (sensor frame) of a frame onto the road surface, at the pose the frame
  // joined the map on (FramePose::map_pose). Without the road surface: nothing.
  void add_scan(const float* x, const float* y, const float* z, const float* intensity, std::size_t n,
                const Eigen::Isometry3d& vehicle_from_sensor, const Eigen::Isometry3d& map_pose);

  // The summary's numbers, in the order they are reported.
  std::vector<std::pair<std::string, double>> metrics() const;
  FileWritten write_map(const std::string& path) const;  // the fine map, as a PCD file
  // The track extracted from the drive, as a track file: a mapping run that could not make one
  // did not do its job.
  TrackWritten write_track(const std::string& path) const;

 private:
  ScanMapper mapper_;
  RoadSurface surface_;
  TrackExtractionParams extraction_;
  bool road_surface_ = false;
  std::vector<Eigen::Vector2d> driven_;
  std::vector<double> driven_roll_;  // the car's roll where it drove, for the banking (NaN: the guess's)
  std::int64_t max_age_ns_ = 0;
  bool level_on_ground_ = true;
  GravityTilt tilt_;
  double level_time_ = 5.0;
  math::EstimateHistory<EstimateExtras> estimates_{256};
  double roll_ = 0, pitch_ = 0, z_ = 0;  // the last registered frame's
  std::uint64_t frames_ = 0, registered_ = 0, no_estimate_ = 0, malformed_ = 0, levelled_ = 0;
  double correction_sum_ = 0, correction_max_ = 0;
};

}  // namespace brickyard::mapping
