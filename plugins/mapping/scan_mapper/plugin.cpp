// mapping.scan_mapper: the paper's mapping (§III-C) as a node (common/scan_mapper.hpp). Each frame
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

#include "common/pcd.hpp"
#include "common/scan_mapper.hpp"
#include "common/track_extraction.hpp"
#include "math/planar_pose.hpp"
#include "../../perception/messages.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <deque>

namespace {

using namespace brickyard;
using namespace brickyard::mapping;

constexpr int kScans = 4;  // LiDARs whose raw returns the road surface may take

struct Settings {
  ScanMapperParams mapper;
  std::string map_file;  // empty: none
  std::string track_file;  // empty: none
  RoadSurfaceParams surface;
  TrackExtractionParams extraction;
  double max_estimate_age = 0.1;
  bool level_on_ground = true;
  double level_window = 4.0, level_time = 5.0;
};

ParamBinding<Settings> bindings() {
  using M = ScanMapperParams;
  ParamBinding<Settings> b;
  b.bind("coarse_voxel", &Settings::mapper, &M::coarse_voxel).in_unit("m").range(0.05, 10)
      .doc("the map registered on first, from the estimate: reaches far");
  b.bind("fine_voxel", &Settings::mapper, &M::fine_voxel).in_unit("m").range(0.02, 10)
      .doc("then on this one, accurate near the answer; also the map written out");
  b.bind("keyframe_distance", &Settings::mapper, &M::keyframe_distance).in_unit("m").range(0, 1000)
      .doc("a frame joins the map once the car has moved this far since the last one");
  b.bind("max_range", &Settings::mapper, &M::max_range).in_unit("m").range(1, 1000).doc("points farther from the car are left out");
  b.bind("max_correction", &Settings::mapper, &M::max_correction).in_unit("m").range(0, 100)
      .doc("a registration moving the estimate farther is not taken");
  b.bind("max_turn", &Settings::mapper, &M::max_turn).in_unit("rad").range(0, 3.14).doc("nor one turning it more");
  b.bind("face_neighbours", &Settings::mapper, &M::registration, &RegistrationParams::face_neighbours)
      .doc("each point matched to its voxel and the 6 sharing a face (VGICP's DIRECT7); off: its own (DIRECT1)");
  b.bind("map_file", &Settings::map_file).doc("the map written here at the end (PCD, binary x y z); empty: not written");
  b.bind("track_file", &Settings::track_file)
      .doc("the track's centre line, widths and banking extracted from the drive (one lap at least; the scan inputs wired), "
           "written here at the end as a track file; empty: not written");
  b.bind("road_cell", &Settings::surface, &RoadSurfaceParams::cell).in_unit("m").range(0.02, 2)
      .doc("the road surface's grid: each cell's mean reflectivity and height");
  b.bind("road_range", &Settings::surface, &RoadSurfaceParams::max_range).in_unit("m").range(1, 200)
      .doc("returns farther from their LiDAR are left out of the road surface (too grazing)");
  b.bind("edge_reflectivity", &Settings::extraction, &TrackExtractionParams::threshold).range(0, 10)
      .doc("the road's edge: where the ground's reflectivity rises past this (asphalt below, grass above)");
  b.bind("station_step", &Settings::extraction, &TrackExtractionParams::station_step).in_unit("m").range(0.1, 50)
      .doc("the extracted track's points: this far apart along the drive");
  b.bind("max_estimate_age", &Settings::max_estimate_age).in_unit("s").range(0, 60)
      .doc("a frame with no estimate within this of its stamp is left out");
  b.bind("level_on_ground", &Settings::level_on_ground)
      .doc("frames join the map with their ground's roll, pitch and height (the walls tilt the whole frame's registration) and, "
           "while the estimate is NORMAL, on its (x, y); off: on the pose found");
  b.bind("level_window", &Settings::level_window).in_unit("s").range(0.5, 60)
      .doc("gravity's level (imu wired): the attitude's drift is its mean less gravity's over this window");
  b.bind("level_time", &Settings::level_time).in_unit("s").range(0.1, 600)
      .doc("and is turned out of the frames joining the map over about this time (a part each frame)");
  b.not_above("fine_voxel", "coarse_voxel");
  return b;
}

struct Ports {
  Input<msgs::PointCloud> points, ground;
  Input<msgs::LocalizationEstimate> estimate;
  std::array<Input<msgs::PointCloud>, kScans> scan;
  Input<msgs::Imu> imu;
  Output<msgs::LocalizationEstimate> pose;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("points", &Ports::points).doc("the ground filter's vertical features, vehicle frame").depth(8);
  b.input("ground", &Ports::ground).doc("the ground filter's ground, vehicle frame, the same frames").depth(8).steps();
  b.input("estimate", &Ports::estimate).doc("the pose estimate (the fusion's), its covariance the prior").depth(64);
  b.inputs("scan", &Ports::scan)
      .doc("a LiDAR's raw returns with their intensities (sensor frame): the road surface").optional().depth(8);
  b.input("imu", &Ports::imu).doc("the IMU (specific force, yaw rate): gravity, the map's level (with level_on_ground)")
      .optional().depth(64);
  b.output("pose", &Ports::pose).doc("the pose found, stamped with the frame; covariance over (x, y, yaw)");
  return b;
}

using CloudPtr = std::shared_ptr<const msgs::PointCloud>;
using EstimatePtr = std::shared_ptr<const msgs::LocalizationEstimate>;

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
    mapper_ = ScanMapper(s.mapper);
    map_file_ = s.map_file;
    track_file_ = s.track_file;
    writable("map_file", map_file_);
    writable("track_file", track_file_);
    surface_ = RoadSurface(s.surface);
    extraction_ = s.extraction;
    io_ = ports().connect(ctx);
    bool any_scan = false;
    for (const auto& in : io_.scan) any_scan = any_scan || in.connected();
    // The track comes from the LiDARs' raw returns: without them a whole drive would end in "no
    // edge found"; said now.
    if (!track_file_.empty() && !any_scan)
      throw BadInput("parameter 'track_file': the track is read from the LiDARs' raw returns, and none of the inputs scan0 .. scan3 is wired");
    max_age_ns_ = static_cast<std::int64_t>(s.max_estimate_age * 1e9);
    level_on_ground_ = s.level_on_ground;
    tilt_ = GravityTilt(s.level_window);
    level_time_ = s.level_time;
  }

  void step(Context& ctx) override {
    for (auto& e : io_.estimate.take()) {
      estimates_.push_back(e);
      if (estimates_.size() > 256) estimates_.pop_front();
    }
    for (auto& m : io_.imu.take())
      if (!estimates_.empty())  // with the newest estimate's speed (both come at 125 Hz)
        tilt_.add_imu(m->header().stamp_ns(), m->accel_x(), m->accel_y(), m->gyro_z(), estimates_.back()->speed());
    for (auto& p : io_.points.take()) {
      features_.push_back(p);
      if (features_.size() > 8) features_.pop_front();
    }
    for (auto& in : io_.scan)
      for (auto& c : in.take()) {
        scans_.push_back(c);
        if (scans_.size() > 4 * kScans) scans_.pop_front();
      }
    for (auto& g : io_.ground.take()) frame(ctx, *g);
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("registered", static_cast<double>(registered_));
    ctx.metric("keyframes", static_cast<double>(mapper_.keyframes()));
    ctx.metric("map_voxels", static_cast<double>(mapper_.fine_map().size()));
    ctx.metric("frames_without_estimate", static_cast<double>(no_estimate_));
    ctx.metric("malformed_clouds", static_cast<double>(malformed_));
    ctx.metric("correction_mean_m", registered_ ? correction_sum_ / static_cast<double>(registered_) : 0.0);
    ctx.metric("correction_max_m", correction_max_);
    ctx.metric("road_cells", static_cast<double>(surface_.cells()));
    ctx.metric("gravity_levelled_frames", static_cast<double>(levelled_));
    if (!map_file_.empty()) {
      try {
        write_pcd(map_file_, mapper_.fine_map());
        ctx.log(LogLevel::info, "map written: " + map_file_ + " (" + std::to_string(mapper_.fine_map().size()) + " points)");
      } catch (const std::exception& e) {
        ctx.fail(e.what());
      }
    }
    if (!track_file_.empty()) write_track(ctx);
  }

 private:
  // A place that cannot be written is said now, not after the laps.
  static void writable(const char* param, const std::string& path) {
    if (path.empty()) return;
    const std::string probe = path + ".part";
    if (!std::ofstream(probe)) throw BadInput(std::string(param) + " '" + path + "': cannot write there (does its folder exist?)");
    std::remove(probe.c_str());
  }

  // The track from the drive: a mapping run that could not make one did not do its job.
  void write_track(Context& ctx) {
    try {
      const ExtractedTrack t = extract_track(surface_, driven_, extraction_, &driven_roll_);
      track::write_centerline_csv(track_file_, t.line);
      ctx.metric("track_points", static_cast<double>(t.line.x.size()));
      ctx.metric("track_sides_found", static_cast<double>(t.sides_found) / (2.0 * static_cast<double>(t.stations)));
      ctx.log(LogLevel::info, "track written: " + track_file_ + " (" + std::to_string(t.line.x.size()) + " points, edges found on " +
                                  std::to_string(t.sides_found) + " of " + std::to_string(2 * t.stations) + " sides)");
    } catch (const std::exception& e) {
      // Also as a metric: `brickyard map build` tells a recording without a track (exit 2) by it.
      ctx.metric("track_error", std::string(e.what()));
      ctx.fail("track_file '" + track_file_ + "' not written: " + e.what());
    }
  }

  // The frame's raw returns (the LiDARs' clouds of its stamp) onto the road surface, at the pose
  // found.
  void add_to_surface(std::int64_t stamp, const Eigen::Isometry3d& pose, bool registered) {
    if (track_file_.empty()) return;
    driven_.emplace_back(pose.translation().x(), pose.translation().y());
    // The car's roll where it drove, for the banking (NaN: not registered, the guess's).
    driven_roll_.push_back(registered ? roll_of(pose) : NAN);
    for (const auto& c : scans_) {
      if (c->header().stamp_ns() != stamp) continue;
      const std::size_t n = c->x().size();
      if (c->y().size() != n || c->z().size() != n || c->intensity().size() != n) continue;
      const perception::SensorPose sp = perception::sensor_pose(*c);
      const Eigen::Isometry3d mount = sp.vehicle_from_sensor().cast<double>();
      if (!mount.matrix().allFinite()) continue;
      surface_.add_scan(c->x().data(), c->y().data(), c->z().data(), c->intensity().data(), n, mount, pose);
    }
  }

  void frame(Context& ctx, const msgs::PointCloud& ground) {
    const std::int64_t stamp = ground.header().stamp_ns();
    Points pts;
    std::size_t n_ground = 0;
    try {
      perception::append_vehicle_points(ground, pts);
      n_ground = pts.size();
      for (const auto& f : features_)
        if (f->header().stamp_ns() == stamp) perception::append_vehicle_points(*f, pts);
    } catch (const std::runtime_error& e) {
      if (malformed_++ == 0) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
      return;
    }
    // The estimate at the frame's stamp: interpolated between the two around it (the fusion's
    // 125 Hz is not the LiDAR's 20 Hz: the nearest one may be 4 ms off, 15 cm at 37 m/s).
    EstimatePtr est, before, after;
    for (const auto& e : estimates_) {
      if (!est || std::llabs(e->header().stamp_ns() - stamp) < std::llabs(est->header().stamp_ns() - stamp)) est = e;
      if (e->header().stamp_ns() <= stamp && (!before || e->header().stamp_ns() > before->header().stamp_ns())) before = e;
      if (e->header().stamp_ns() >= stamp && (!after || e->header().stamp_ns() < after->header().stamp_ns())) after = e;
    }
    if (!est || std::llabs(est->header().stamp_ns() - stamp) > max_age_ns_ || !std::isfinite(est->x()) ||
        !std::isfinite(est->y()) || !std::isfinite(est->yaw())) {
      ++no_estimate_;
      return;
    }
    math::PlanarPose at{est->x(), est->y(), est->yaw()};
    if (before && after)
      at = math::interpolate_pose(before->header().stamp_ns(), {before->x(), before->y(), before->yaw()},
                                  after->header().stamp_ns(), {after->x(), after->y(), after->yaw()}, stamp);
    const double ex = at.x, ey = at.y, eyaw = at.yaw;
    ++frames_;
    // The guess: the estimate's (x, y, yaw), with the height, roll and pitch the last frame found
    // (the estimate is planar; a banked turn tilts the car).
    Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
    guess.linear() = attitude(eyaw, pitch_, roll_);
    guess.translation() = Eigen::Vector3d(ex, ey, z_);
    Eigen::Matrix3d cov;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov(a, b) = est->covariance()[3 * a + b];
    const Points ground_pts(pts.begin(), pts.begin() + static_cast<long>(n_ground));
    // Gravity's level: a part of the attitude's drift turned out each frame (GravityTilt).
    Tilt tilt;
    if (level_on_ground_ && io_.imu.connected() && tilt_.correction(stamp, level_time_, tilt)) ++levelled_;
    const ScanResult r = mapper_.add(pts, guess, planar_information(cov), level_on_ground_ ? &ground_pts : nullptr, tilt,
                                     est->status() == 0);  // NORMAL: its GNSS's
    if (r.registered) {
      ++registered_;
      const double c = std::hypot(r.pose.translation().x() - ex, r.pose.translation().y() - ey);
      correction_sum_ += c;
      correction_max_ = std::max(correction_max_, c);
      pitch_ = pitch_of(r.map_pose);
      roll_ = roll_of(r.map_pose);
      z_ = r.map_pose.translation().z();
      tilt_.add_frame(stamp, roll_, pitch_);
    }
    add_to_surface(stamp, r.map_pose, r.registered);
    msgs::LocalizationEstimate m;
    m.header().stamp_ns(stamp);
    m.header().seq(seq_++);
    m.header().frame_id("map");
    m.x(r.pose.translation().x());
    m.y(r.pose.translation().y());
    const Eigen::Vector3d fwd = r.pose.linear().col(0);
    m.yaw(std::atan2(fwd.y(), fwd.x()));
    m.speed(est->speed());
    m.yaw_rate(est->yaw_rate());
    const Eigen::Matrix3d pc = planar_covariance(r.covariance);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m.covariance()[3 * a + b] = pc(a, b);
    m.update_case(r.registered ? 2 : 0);
    m.status(est->status());
    io_.pose.publish(std::move(m));
  }

  ScanMapper mapper_;
  std::string map_file_, track_file_;
  RoadSurface surface_;
  TrackExtractionParams extraction_;
  std::vector<Eigen::Vector2d> driven_;
  std::vector<double> driven_roll_;
  std::deque<CloudPtr> scans_;
  std::int64_t max_age_ns_ = 0;
  bool level_on_ground_ = true;
  GravityTilt tilt_;
  double level_time_ = 5.0;
  std::uint64_t levelled_ = 0;
  Ports io_;
  std::deque<EstimatePtr> estimates_;
  std::deque<CloudPtr> features_;
  double roll_ = 0, pitch_ = 0, z_ = 0;
  std::uint32_t seq_ = 0;
  std::uint64_t frames_ = 0, registered_ = 0, no_estimate_ = 0, malformed_ = 0;
  double correction_sum_ = 0, correction_max_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ScanMapperNode)
