#pragma once
// Where the scene (scene.hpp) sends what it draws: the live server, to the clients subscribed to a
// channel, or a recording (record/recorded_scene.hpp), every message. The scene asks before it
// draws: a channel nobody wants costs nothing.
#include <cstddef>
#include <cstdint>
#include <string>

namespace brickyard::fw {

class SceneOutlet {
 public:
  virtual ~SceneOutlet() = default;
  // A channel, its id for publish(); 0 when the outlet takes none of it. `cloud`: point clouds.
  virtual std::uint32_t add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                                    const std::string& schema_encoding, const std::string& schema, bool cloud = false) = 0;
  // Whether a message on the channel now would be taken.
  virtual bool wanted(std::uint32_t channel) const = 0;
  virtual void publish(std::uint32_t channel, std::uint64_t stamp_ns, const unsigned char* data, std::size_t size) = 0;
};

}  // namespace brickyard::fw
