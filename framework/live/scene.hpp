#pragma once
// The run's scene in Foxglove's own schemas, for its 3D panel (docs/live.md), served beside the
// wires by the live server, JSON-encoded:
//   /tf                foxglove.FrameTransform: map → truth (the simulator's car, VehicleState),
//                      map → vehicle (the car stack's estimate, LocalizationEstimate; the truth
//                      when the graph has no estimator)
//   /scene/track       foxglove.SceneUpdate: the car's map's edges (TrackMap), the simulator's
//                      walls and pylons (TrackWorld)
//   /scene/path        the planned path (Path), coloured by the system manager's mode
//   /scene/wall        the fitted wall (WallEstimate), in the vehicle frame
//   /scene/obstacles   the obstacles (ObstacleList), boxes in the vehicle frame
//   /lidar/NODE.PORT   foxglove.PointCloud: each LiDAR's cloud, placed by its mount
// Made only while a client is subscribed to the channel. Each message type's picture is its
// converter's (scene_converter.hpp), found by the type's name.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace brickyard::fw {

class SceneOutlet;
namespace live_scene {
struct SceneState;
}

class LiveScene {
 public:
  // Adds its fixed channels to the outlet (the live server, before it starts; or a recording).
  explicit LiveScene(SceneOutlet& outlet);
  ~LiveScene();
  // What the scene makes of a topic of this type: a function to call with each sample (the
  // message object and the run's clock), or an empty one. Called while the graph is built.
  std::function<void(const void*, std::uint64_t)> handler(const std::string& topic, const std::string& type);

 private:
  std::shared_ptr<live_scene::SceneState> state_;  // shared with the handlers, which may outlive the scene
};

}  // namespace brickyard::fw
