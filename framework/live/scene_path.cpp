// /scene/path (foxglove.SceneUpdate): the planned path (Path), coloured by the system manager's
// mode (ModeStatus).
#include "live/scene_converter.hpp"
#include "live/scene_draw.hpp"

#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/Path.h>

namespace brickyard::fw::live_scene {
namespace {

Colour path_colour(SceneState& s) {
  std::lock_guard<std::mutex> l(s.mode_mutex);
  if (s.mode == "PATH") return {0.2, 0.9, 0.3};
  if (s.mode == "WALL_FOLLOW") return {1.0, 0.6, 0.1};
  if (s.mode == "SAFE_STOP") return {1.0, 0.2, 0.2};
  return {0.9, 0.9, 0.9};
}

// The system manager's ModeStatus is the one that names the controller it hands the car to
// (active_controller); the localization manager's (the estimator's mode) names none. Told apart
// by what the message says, not by the node's name, so the path is coloured whatever the graph
// calls its manager.
SceneHandler mode_status(const std::shared_ptr<SceneState>& s, const std::string&) {
  return [s](const void* p, std::uint64_t) {
    const auto& status = *static_cast<const msgs::ModeStatus*>(p);
    if (status.active_controller().empty()) return;
    std::lock_guard<std::mutex> l(s->mode_mutex);
    s->mode = status.mode_name();
  };
}

SceneHandler planned_path(const std::shared_ptr<SceneState>& s, const std::string& topic) {
  return [s, topic](const void* p, std::uint64_t ns) {
    if (!s->server.wanted(s->path)) return;
    const auto& path = *static_cast<const msgs::Path*>(p);
    Points pts;
    for (const auto& q : path.poses()) pts.add(q.x(), q.y(), 0.1);
    JsonText lines;
    line_strip(lines, pts, 0.3, path_colour(*s));
    s->send(s->path, ns, scene_update(ns, "map", topic, lines, JsonText(), JsonText()));
  };
}

}  // namespace

std::vector<SceneConverterEntry> path_converters() {
  return {
      converter<msgs::ModeStatus>(mode_status),
      converter<msgs::Path>(planned_path),
  };
}

}  // namespace brickyard::fw::live_scene
