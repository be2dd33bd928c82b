#pragma once
// The live scene's converters: per message type, what the scene makes of a topic of that type
// (scene.hpp). A converter is a small named function in the file of its kind (scene_vehicle.cpp,
// scene_track.cpp, scene_path.cpp, scene_perception.cpp, scene_cloud.cpp), listed there by its
// type's name from the SDK's message traits; scene.cpp looks a topic's type up in those lists.
// A new message type is its converter and one line in its file's list.
#include "live/scene_outlet.hpp"

#include <brickyard/message_traits.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::fw::live_scene {

// What the converters share: the outlet, the fixed channels, and what one topic tells another.
struct SceneState {
  explicit SceneState(SceneOutlet& s) : server(s) {}
  void send(std::uint32_t ch, std::uint64_t ns, const std::string& text) {
    server.publish(ch, ns, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  }

  SceneOutlet& server;  // the live server, or a recording
  std::uint32_t tf = 0, track = 0, path = 0, wall = 0, obstacles = 0;
  bool has_estimate = false;  // the graph has an estimator: the vehicle frame is its estimate, not the truth
  // A frame's transform at most every 20 ms of the run (50 Hz; Foxglove interpolates between
  // them): the truth comes at 500 Hz, and a JSON message each was a fifth of the main job's time.
  std::atomic<std::uint64_t> next_truth{0}, next_vehicle{0};
  std::mutex mode_mutex;
  std::string mode;  // the system manager's, for the path's colour
};

// Called with each sample of a topic: the message object and the run's clock.
using SceneHandler = std::function<void(const void*, std::uint64_t)>;
// A topic's handler, made while the graph is built (every topic is seen before the run starts).
using SceneConverter = SceneHandler (*)(const std::shared_ptr<SceneState>& scene, const std::string& topic);

struct SceneConverterEntry {
  std::string_view type;  // message_traits<T>::name
  SceneConverter make;
};
template <class T>
SceneConverterEntry converter(SceneConverter make) {
  return {message_traits<T>::name, make};
}

// Each kind's list of converters, by message type.
std::vector<SceneConverterEntry> vehicle_converters();     // scene_vehicle.cpp: the /tf frames
std::vector<SceneConverterEntry> track_converters();       // scene_track.cpp: /scene/track
std::vector<SceneConverterEntry> path_converters();        // scene_path.cpp: /scene/path
std::vector<SceneConverterEntry> perception_converters();  // scene_perception.cpp: /scene/wall, /scene/obstacles
std::vector<SceneConverterEntry> cloud_converters();       // scene_cloud.cpp: /lidar/NODE.PORT

}  // namespace brickyard::fw::live_scene
