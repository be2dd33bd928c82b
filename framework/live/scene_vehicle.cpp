// The scene's frames on /tf (foxglove.FrameTransform): map → truth from the simulator's car,
// map → vehicle from the car stack's estimate (the truth when the graph has no estimator).
#include "live/scene_converter.hpp"
#include "live/scene_draw.hpp"

#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/VehicleState.h>

namespace brickyard::fw::live_scene {
namespace {

// Whether a frame's next transform is due (someone subscribed, 20 ms since its last), taking
// the turn when it is.
bool due(SceneState& s, std::atomic<std::uint64_t>& next, std::uint64_t ns) {
  if (!s.server.wanted(s.tf)) return false;
  std::uint64_t at = next.load();
  return ns >= at && next.compare_exchange_strong(at, ns + 20'000'000);
}

void send_transform(SceneState& s, std::uint64_t ns, const char* child, double x, double y, double z, double roll, double pitch,
                    double yaw) {
  JsonText w;
  w.open('{').key("timestamp");
  stamp(w, ns);
  w.key("parent_frame_id").str("map").key("child_frame_id").str(child).key("translation");
  vec(w, x, y, z);
  w.key("rotation");
  quat(w, quat(roll, pitch, yaw));
  w.close('}');
  s.send(s.tf, ns, w.text());
}

SceneHandler vehicle_state(const std::shared_ptr<SceneState>& s, const std::string&) {
  return [s](const void* p, std::uint64_t ns) {
    const auto& v = *static_cast<const msgs::VehicleState*>(p);
    const bool truth = due(*s, s->next_truth, ns), vehicle = !s->has_estimate && due(*s, s->next_vehicle, ns);
    if (!truth && !vehicle) return;
    if (truth) send_transform(*s, ns, "truth", v.x(), v.y(), v.z(), v.roll(), v.pitch(), v.yaw());
    if (vehicle) send_transform(*s, ns, "vehicle", v.x(), v.y(), v.z(), v.roll(), v.pitch(), v.yaw());
  };
}

SceneHandler localization_estimate(const std::shared_ptr<SceneState>& s, const std::string&) {
  s->has_estimate = true;  // (every topic is seen before the run starts)
  return [s](const void* p, std::uint64_t ns) {
    if (!due(*s, s->next_vehicle, ns)) return;
    const auto& e = *static_cast<const msgs::LocalizationEstimate*>(p);
    send_transform(*s, ns, "vehicle", e.x(), e.y(), 0, 0, 0, e.yaw());
  };
}

}  // namespace

std::vector<SceneConverterEntry> vehicle_converters() {
  return {
      converter<msgs::VehicleState>(vehicle_state),
      converter<msgs::LocalizationEstimate>(localization_estimate),
  };
}

}  // namespace brickyard::fw::live_scene
