#include "live/scene.hpp"

#include "live/scene_outlet.hpp"
#include "live/scene_converter.hpp"

#include <string_view>
#include <unordered_map>

namespace brickyard::fw {

namespace {
using live_scene::SceneConverter;
using live_scene::SceneState;

const char* kSchema = R"({"type":"object"})";  // Foxglove knows its schemas by name

std::uint32_t channel(SceneState& s, const std::string& topic, const std::string& schema) {
  return s.server.add_channel(topic, "json", schema, "jsonschema", kSchema);
}

// Every converter, by its message type's name (the SDK's message traits).
const std::unordered_map<std::string_view, SceneConverter>& converters() {
  static const auto table = [] {
    std::unordered_map<std::string_view, SceneConverter> t;
    for (const auto& kind : {live_scene::vehicle_converters(), live_scene::track_converters(), live_scene::path_converters(),
                             live_scene::perception_converters(), live_scene::cloud_converters()})
      for (const auto& entry : kind) t.emplace(entry.type, entry.make);
    return t;
  }();
  return table;
}
}  // namespace

LiveScene::LiveScene(SceneOutlet& outlet) : state_(std::make_shared<SceneState>(outlet)) {
  SceneState& s = *state_;
  s.tf = channel(s, "/tf", "foxglove.FrameTransform");
  s.track = channel(s, "/scene/track", "foxglove.SceneUpdate");
  s.path = channel(s, "/scene/path", "foxglove.SceneUpdate");
  s.wall = channel(s, "/scene/wall", "foxglove.SceneUpdate");
  s.obstacles = channel(s, "/scene/obstacles", "foxglove.SceneUpdate");
}

LiveScene::~LiveScene() = default;

std::function<void(const void*, std::uint64_t)> LiveScene::handler(const std::string& topic, const std::string& type) {
  const auto& table = converters();
  const auto found = table.find(type);
  if (found == table.end()) return {};
  return found->second(state_, topic);
}

}  // namespace brickyard::fw
