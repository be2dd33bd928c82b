#pragma once
// The scene (live/scene.hpp) into a recording: /tf and /scene/* in Foxglove's own schemas, beside
// the wires, so a recording opened in Foxglove shows the 3D scene the live view shows (issue 45,
// docs/recording.md). A channel is added to the file with its first message: a process that draws
// none of it (one of a split run's) records none. MCAP only (a .db3 takes none); the LiDARs'
// clouds are left out (their own channels hold them where they are recorded: drawn again, a cloud
// would double the file).
#include "live/scene_outlet.hpp"
#include "record/recorder.hpp"

#include <mutex>
#include <vector>

namespace brickyard::fw {

class RecordedScene : public SceneOutlet {
 public:
  explicit RecordedScene(Recorder& r) : recorder_(r) {}
  std::uint32_t add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                            const std::string& schema_encoding, const std::string& schema, bool cloud = false) override {
    if (cloud) return 0;
    std::lock_guard<std::mutex> l(m_);
    channels_.push_back({topic, encoding, schema_name, schema_encoding, schema, 0});
    return static_cast<std::uint32_t>(channels_.size());
  }
  bool wanted(std::uint32_t channel) const override { return channel != 0; }
  void publish(std::uint32_t channel, std::uint64_t stamp_ns, const unsigned char* data, std::size_t size) override {
    int id = 0;
    {
      std::lock_guard<std::mutex> l(m_);
      if (channel == 0 || channel > channels_.size()) return;
      Channel& c = channels_[channel - 1];
      if (c.id == 0) c.id = recorder_.add_channel(c.topic, c.encoding, c.schema_name, c.schema_encoding, c.schema), c.id = c.id ? c.id : -1;
      id = c.id;
    }
    if (id > 0) recorder_.write(id, static_cast<std::int64_t>(stamp_ns), data, size);
  }

 private:
  struct Channel {
    std::string topic, encoding, schema_name, schema_encoding, schema;
    int id = 0;  // the recorder's, once added; -1: the recording takes none
  };
  Recorder& recorder_;
  std::mutex m_;
  std::vector<Channel> channels_;
};

}  // namespace brickyard::fw
