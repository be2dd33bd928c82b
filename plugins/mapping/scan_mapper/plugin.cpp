// mapping.scan_mapper: the paper's mapping (§III-C) as a node (common/mapping_run.hpp). Each frame
// of the ground filter's voxels (vertical features and ground, vehicle frame) is registered onto
// the map so far from the pose estimate of its stamp, that estimate as the prior; the pose found
// is published as a second estimate with its covariance. The frame joins the map with its
// ground's roll, pitch and height (levelled by gravity when the IMU is wired), on the estimate's
// (x, y) while that is GNSS's, else on the pose found (ScanResult::map_pose). At the end the map
// is written as a PCD file (`map_file`) and the track extracted (`track_file`).
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/plugin.hpp>

#include "mapping/common/mapping_run.hpp"
#include "mapping/frame_io.hpp"
#include "params.hpp"
#include "ports.hpp"
#include "perception/messages.hpp"

#include <deque>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::mapping;

using CloudPtr = std::shared_ptr<const msgs::PointCloud>;

// A place that cannot be written is said now, not after the laps.
void writable(const char* param, const std::string& path) {
  if (const std::string problem = unwritable(param, path); !problem.empty()) throw BadInput(problem);
}

class ScanMapperNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("mapping.scan_mapper", "1.0.0")
        .describe("each frame registered onto the map so far (voxelized GICP, the pose estimate as prior) and added to it; "
                  "the pose found published as a second estimate; the map written as a PCD file at the end")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    const Settings s = bindings().read(ctx.params());
    run_.emplace(s, !s.track_file.empty());
    map_file_ = s.map_file;
    track_file_ = s.track_file;
    writable("map_file", map_file_);
    writable("track_file", track_file_);
    io_ = ports().connect(ctx);
    bool any_scan = false;
    for (const auto& in : io_.scan) any_scan = any_scan || in.connected();
    // The track comes from the LiDARs' raw returns: without them a whole drive would end in "no
    // edge found"; said now.
    if (!track_file_.empty() && !any_scan)
      throw BadInput("parameter 'track_file': the track is read from the LiDARs' raw returns, and none of the inputs scan0 .. scan3 "
                     "is wired");
  }

  void step(Context& ctx) override {
    for (auto& e : io_.estimate.take())
      run_->estimate(e->header().stamp_ns(), {e->x(), e->y(), e->yaw()}, {e->speed(), e->yaw_rate(), e->covariance(), e->status()});
    for (auto& m : io_.imu.take()) run_->imu(m->header().stamp_ns(), m->accel_x(), m->accel_y(), m->gyro_z());
    for (auto& p : io_.points.take()) features_.add(p);
    for (auto& in : io_.scan)
      for (auto& c : in.take()) {
        scans_.push_back(c);
        if (scans_.size() > 4 * kScans) scans_.pop_front();
      }
    for (auto& g : io_.ground.take()) frame(ctx, *g);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : run_->metrics()) ctx.metric(name, value);
    if (!map_file_.empty()) {
      const FileWritten map = run_->write_map(map_file_);
      if (map.ok) ctx.log(LogLevel::info, map.message);
      else ctx.fail(map.message);
    }
    if (track_file_.empty()) return;
    const TrackWritten track = run_->write_track(track_file_);
    if (track.ok) {
      ctx.metric("track_points", track.points);
      ctx.metric("track_sides_found", track.sides_found);
      ctx.log(LogLevel::info, track.message);
    } else {
      ctx.metric("track_error", track.error);  // `brickyard map build` tells a recording without a track (exit 2) by it
      ctx.fail(track.message);
    }
  }

 private:
  void frame(Context& ctx, const msgs::PointCloud& ground) {
    const std::int64_t stamp = ground.header().stamp_ns();
    Points pts;
    std::size_t n_ground = 0;
    try {
      features_.assemble(ground, pts, &n_ground);
    } catch (const std::runtime_error& e) {
      if (run_->malformed()) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
      return;
    }
    const std::optional<FramePose> found = run_->frame(stamp, pts, n_ground, io_.imu.connected());
    if (!found) return;
    // The frame's raw returns (the LiDARs' clouds of its stamp) onto the road surface, at the pose found.
    for (const auto& c : scans_) {
      const std::size_t n = c->x().size();
      if (c->header().stamp_ns() != stamp || c->y().size() != n || c->z().size() != n || c->intensity().size() != n) continue;
      const Eigen::Isometry3d mount = perception::sensor_pose(*c).vehicle_from_sensor().cast<double>();
      if (!mount.matrix().allFinite()) continue;
      run_->add_scan(c->x().data(), c->y().data(), c->z().data(), c->intensity().data(), n, mount, found->map_pose);
    }
    io_.pose.publish(pose_message(*found, seq_++));
  }

  std::optional<MappingRun> run_;
  std::string map_file_, track_file_;
  Ports io_;
  FrameFeatures features_;
  std::deque<CloudPtr> scans_;
  std::uint32_t seq_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ScanMapperNode)
