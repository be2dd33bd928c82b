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
#include "perception/object_tracker/tracker_settings.hpp"

#include "map_msg.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;
using namespace brickyard::perception;

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
        .parameters(tracker_bindings())
        .check(&plugins::check_vehicle_file<&tracker_bindings, &TrackerSettings::vehicle>);
  }

  void configure(Context& ctx) override {
    settings_ = tracker_bindings().read(ctx.params());
    const vehicle::Vehicle car = plugins::read_vehicle(ctx, settings_.vehicle);
    settings_.tracker.car.length = car.front + car.rear;
    settings_.tracker.car.width = 2 * car.half_width;
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
      for (const auto& d : o->obstacles()) {
        detections_.push_back({d.x(), d.y(), d.size_x(), d.size_y(), {}, d.box_yaw()});
        for (std::size_t k = 0; k < std::min(d.outline_x().size(), d.outline_y().size()); ++k)
          detections_.back().outline.emplace_back(d.outline_x()[k], d.outline_y()[k]);
      }
      tracker_->update(o->header().stamp_ns() * 1e-9, *ego, detections_);
      publish(o->header().stamp_ns());
    }
  }

  void deactivate(Context& ctx) override {
    ctx.metric("frames", static_cast<double>(frames_));
    ctx.metric("frames_unplaced", static_cast<double>(unplaced_));
    ctx.metric("births", tracker_ ? static_cast<double>(tracker_->births()) : 0.0);
    ctx.metric("deaths", tracker_ ? static_cast<double>(tracker_->deaths()) : 0.0);
    ctx.metric("detections_off_road", tracker_ ? static_cast<double>(tracker_->off_road()) : 0.0);
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

  TrackerSettings settings_;
  std::unique_ptr<track::Track> track_;
  std::optional<ObjectTracker> tracker_;
  EgoHistory ego_;
  std::vector<Detection> detections_;
  Ports io_;
  std::uint64_t frames_ = 0, unplaced_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(ObjectTrackerNode)
