// perception.object_tracker: the obstacle detector's frames followed into tracked objects on the
// track (s, d), placed by the car's pose at each frame's stamp (common/object_tracker.hpp,
// docs/tracking.md).
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/TrackedObjectList.h>
#include <brickyard/plugin.hpp>

#include "perception/common/ego_history.hpp"
#include "perception/common/object_tracker.hpp"
#include "perception/object_tracker/track_message.hpp"

#include "map_msg.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::perception;

struct Settings {
  TrackerParams tracker;
  PredictionParams prediction;
  bool confirmed_only = true;
};

ParamBinding<Settings> bindings() {
  using T = TrackerParams;
  ParamBinding<Settings> b;
  b.bind("accel_sigma", &Settings::tracker, &T::accel_sigma).in_unit("m/s^2").range(0.01, 100).doc("white acceleration along the track");
  b.bind("lateral_accel_sigma", &Settings::tracker, &T::lateral_accel_sigma).in_unit("m/s^2").range(0.01, 100).doc("white acceleration across it");
  b.bind("meas_sigma", &Settings::tracker, &T::meas_sigma).in_unit("m").range(0.001, 10).doc("a detection's position, 1 sigma");
  b.bind("meas_sigma_per_m", &Settings::tracker, &T::meas_sigma_per_m).range(0, 1).doc("m of spread added per m of range");
  b.bind("gate", &Settings::tracker, &T::gate).range(0.1, 1000).doc("chi-square (2 dof) within which a detection may be a track's");
  b.bind("birth_speed_sigma", &Settings::tracker, &T::birth_speed_sigma).in_unit("m/s").range(0.1, 200).doc("a new track's velocity spread");
  b.bind("confirm_hits", &Settings::tracker, &T::confirm_hits).range(1, 30).doc("hits that confirm a track ...");
  b.bind("confirm_window", &Settings::tracker, &T::confirm_window).range(1, 30).doc("... within its first this many frames");
  b.bind("max_misses", &Settings::tracker, &T::max_misses).range(0, 1000).doc("frames a confirmed track may go unseen");
  b.bind("max_sigma", &Settings::tracker, &T::max_sigma).in_unit("m").range(0.01, 1000).doc("a track more spread than this is dropped");
  b.bind("confirmed_only", &Settings::confirmed_only).doc("publish only confirmed tracks");
  b.bind("horizon_s", &Settings::prediction, &PredictionParams::horizon_s).in_unit("s").range(0, 30).doc("each track's path foreseen this far (0: none)");
  b.bind("prediction_step_s", &Settings::prediction, &PredictionParams::step_s).in_unit("s").range(0.01, 5).doc("between its points");
  b.not_above("confirm_hits", "confirm_window");
  return b;
}

struct Ports {
  Input<msgs::TrackMap> map;
  Input<msgs::ObstacleList> obstacles;
  Input<msgs::LocalizationEstimate> estimate;
  Output<msgs::TrackedObjectList> tracks;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("map", &Ports::map).doc("the track: objects are followed along it").depth(1);
  b.input("obstacles", &Ports::obstacles).doc("a frame's obstacles (vehicle frame)").depth(4).steps();
  b.input("estimate", &Ports::estimate).doc("the car's pose: each frame placed by the pose at its stamp").depth(64);
  b.output("tracks", &Ports::tracks).doc("the objects followed, map frame, after each frame");
  return b;
}

class ObjectTrackerNode : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("perception.object_tracker", "1.0.0")
        .describe("tracked objects (position, velocity, heading; births and deaths) from frames of obstacles")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    settings_ = bindings().read(ctx.params());
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    if (!tracker_) start(ctx);
    for (const auto& e : io_.estimate.take())
      ego_.add({e->header().stamp_ns(), e->x(), e->y(), e->yaw(), e->speed(), e->yaw_rate()});
    for (const auto& o : io_.obstacles.take()) {
      const auto ego = ego_.at(o->header().stamp_ns());
      if (!ego || !tracker_) {  // no pose of the car then, or no track yet: the frame cannot be placed
        ++unplaced_;
        continue;
      }
      detections_.clear();
      for (const auto& d : o->obstacles()) detections_.push_back({d.x(), d.y(), d.size_x(), d.size_y()});
      tracker_->update(o->header().stamp_ns() * 1e-9, *ego, detections_);
      publish(o->header().stamp_ns());
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("frames_unplaced", static_cast<double>(unplaced_));
    ctx.metric("births", tracker_ ? static_cast<double>(tracker_->births()) : 0.0);
    ctx.metric("deaths", tracker_ ? static_cast<double>(tracker_->deaths()) : 0.0);
  }

 private:
  // The tracker, once the map has come: the track it follows objects along.
  void start(Context& ctx) {
    const auto m = io_.map.latest();
    if (!m) return;
    try {
      track_ = std::make_unique<track::Track>(plugins::from_message(*m));
    } catch (const std::invalid_argument& e) {
      throw BadInput(std::string("input 'map': ") + e.what());
    }
    tracker_.emplace(*track_, settings_.tracker);
    ctx.log(LogLevel::info, "following objects along " + m->name());
  }

  void publish(std::int64_t stamp_ns) {
    msgs::TrackedObjectList out;
    out.header().stamp_ns(stamp_ns);
    out.header().seq(static_cast<std::uint32_t>(frames_++));
    out.header().frame_id("map");
    for (const Track& t : tracker_->tracks())
      if (t.confirmed || !settings_.confirmed_only) out.objects().push_back(track_message(t, *track_, settings_.prediction));
    io_.tracks.publish(std::move(out));
  }

  Settings settings_;
  std::unique_ptr<track::Track> track_;
  std::optional<ObjectTracker> tracker_;
  EgoHistory ego_;
  std::vector<Detection> detections_;
  Ports io_;
  std::uint64_t frames_ = 0, unplaced_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ObjectTrackerNode)
