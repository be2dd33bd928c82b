// mapping.map_localizer: localization on a prior map of the track (common/map_localizer.hpp).
// Each frame of the ground filter's voxels (vertical features and ground, vehicle frame) is
// registered onto the map file from the pose estimate of its stamp; the pose found is published
// with its covariance (what the map cannot tell, said there), a witness of the car's position
// independent of GNSS. Wired into the fusion's scan_pose, it carries the car through a GNSS outage.
#include <brickyard/plugin.hpp>

#include "mapping/common/map_coverage.hpp"
#include "mapping/common/map_localization_run.hpp"
#include "mapping/common/pcd.hpp"
#include "mapping/frame_io.hpp"
#include "params.hpp"
#include "ports.hpp"

#include "track/centre_line.hpp"

#include <cstdio>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::mapping;

// A map far from the track it is used on (another track's, or in another frame) is refused.
template <class Files> void check_covers_track(const Files& files, const LocalizerSettings& s, const std::string& map_path, const Points& map) {
  const std::string path = files.find_file(s.track);
  track::CenterLine line;
  try {
    line = track::load_centerline_csv(path);
  } catch (const std::exception& e) {
    throw BadInput(std::string("parameter 'track': ") + e.what());
  }
  const double share = share_near_map(map, line.x, line.y, s.track_reach);
  if (share >= s.track_share) return;
  char b[160];
  std::snprintf(b, sizeof b, ": far from the track: %.0f %% of its centre line lies within %.0f m of the map (%.0f %% needed)", 100 * share,
                s.track_reach, 100 * s.track_share);
  throw BadInput("parameter 'map_file': " + map_path + b + " (" + path + ")");
}

// The map file: read, or refused naming it (at validation and at configure alike).
template <class Files> Points read_map(const Files& files, const LocalizerSettings& s) {
  if (s.map_file.empty()) throw BadInput("parameter 'map_file': empty: the track's map is needed (scripts/track-map makes one)");
  const std::string path = files.find_file(s.map_file);
  Points map;
  try {
    map = read_pcd(path);
  } catch (const std::exception& e) {
    throw BadInput(std::string("parameter 'map_file': ") + e.what());
  }
  if (map.empty()) throw BadInput("parameter 'map_file': " + path + ": the map holds no point");
  if (!s.track.empty()) check_covers_track(files, s, path, map);
  return map;
}

void check(const CheckView& v) { read_map(v, localizer_bindings().read(v.params())); }

class MapLocalizerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("mapping.map_localizer", "1.0.0")
        .describe("each frame registered onto a prior map of the track (voxelized GICP, seeded by the estimate); the pose found "
                  "published with its covariance, a position independent of GNSS")
        .with_ports(localizer_ports())
        .parameters(localizer_bindings())
        .delivered_after("latency_s")
        .check(&check);
  }

  void configure(Context& ctx) override {
    const LocalizerSettings s = localizer_bindings().read(ctx.params());
    run_.emplace(read_map(ctx, s), s);
    io_ = localizer_ports().connect(ctx);
    ctx.log(LogLevel::info, "map " + s.map_file + ": " + std::to_string(run_->localizer().map_points()) + " points, " +
                                std::to_string(run_->localizer().fine_map().size()) + " voxels");
  }

  void step(Context& ctx) override {
    for (auto& e : io_.estimate.take())
      run_->estimate(e->header().stamp_ns(), {e->x(), e->y(), e->yaw()}, {e->speed(), e->yaw_rate(), e->covariance(), e->status()});
    for (auto& p : io_.points.take()) features_.add(p);
    for (auto& g : io_.ground.take()) frame(ctx, *g);
  }

  void deactivate(Context& ctx) override {
    for (const auto& [name, value] : run_->metrics()) ctx.metric(name, value);
  }

 private:
  void frame(Context& ctx, const msgs::PointCloud& ground) {
    Points pts;
    try {
      features_.assemble(ground, pts);
    } catch (const std::runtime_error& e) {
      if (run_->malformed()) ctx.log(LogLevel::warn, std::string(e.what()) + ": frame skipped");
      return;
    }
    if (const std::optional<FramePose> found = run_->frame(ground.header().stamp_ns(), pts))
      io_.pose.publish(pose_message(*found, seq_++));
  }

  std::optional<MapLocalizationRun> run_;
  LocalizerPorts io_;
  FrameFeatures features_;
  std::uint32_t seq_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(MapLocalizerNode)
