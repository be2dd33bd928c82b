#pragma once
// The scene (live/scene.hpp) into a recording: /tf and /scene/* in Foxglove's own schemas, beside
// the wires, so a recording opened in Foxglove shows the 3D scene the live view shows (issue 45,
// docs/recording.md). MCAP only (a .db3 takes none); the LiDARs' clouds are left out (their own
// channels hold them where they are recorded: drawn again, a cloud would double the file).
#include "live/scene_outlet.hpp"
#include "record/recorder.hpp"

namespace brickyard::fw {

class RecordedScene : public SceneOutlet {
 public:
  explicit RecordedScene(Recorder& r) : recorder_(r) {}
  std::uint32_t add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                            const std::string& schema_encoding, const std::string& schema, bool cloud = false) override {
    if (cloud) return 0;
    const int id = recorder_.add_channel(topic, encoding, schema_name, schema_encoding, schema);
    return id > 0 ? static_cast<std::uint32_t>(id) : 0;
  }
  bool wanted(std::uint32_t channel) const override { return channel != 0; }
  void publish(std::uint32_t channel, std::uint64_t stamp_ns, const unsigned char* data, std::size_t size) override {
    recorder_.write(static_cast<int>(channel), static_cast<std::int64_t>(stamp_ns), data, size);
  }

 private:
  Recorder& recorder_;
};

}  // namespace brickyard::fw
