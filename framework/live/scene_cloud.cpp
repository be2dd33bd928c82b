// /lidar/NODE.PORT: each point cloud (PointCloud) as foxglove::PointCloud, placed by the sensor's
// mount in the vehicle frame.
#include "live/scene_converter.hpp"
#include "live/scene_draw.hpp"

#include <brickyard/msgs/PointCloud.h>

#include <algorithm>
#include <cstring>

namespace brickyard::fw::live_scene {
namespace {

// foxglove::PointCloud in OMG IDL, CDR-encoded: a cloud is megabytes, which JSON would carry as
// base64 text (7 ms a cloud to make, 40 % of the main job's time with three LiDARs at 20 Hz).
const char* kPointCloudIdl = R"(module foxglove {
struct Time { uint32 sec; uint32 nsec; };
struct Vector3 { double x; double y; double z; };
struct Quaternion { double x; double y; double z; double w; };
struct Pose { Vector3 position; Quaternion orientation; };
struct PackedElementField { string name; uint32 offset; uint32 type; };
struct PointCloud { Time timestamp; string frame_id; Pose pose; uint32 point_stride; sequence<PackedElementField> fields; sequence<uint8> data; };
};
)";

// Little-endian CDR (XCDR1), each primitive aligned to its size after the 4-byte header.
struct CdrWriter {
  std::string out{"\x00\x01\x00\x00", 4};
  template <typename T>
  void num(T v) {
    while ((out.size() - 4) % sizeof(T)) out.push_back('\0');
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void str(const std::string& s) {
    num(static_cast<std::uint32_t>(s.size() + 1));
    out.append(s.c_str(), s.size() + 1);
  }
};

// The cloud as a foxglove::PointCloud: x, y, z and intensity as float32, 16 bytes a point.
CdrWriter foxglove_cloud(const msgs::PointCloud& c, std::uint64_t ns) {
  const std::size_t n = std::min({c.x().size(), c.y().size(), c.z().size()});
  CdrWriter w;
  w.num(static_cast<std::uint32_t>(ns / 1'000'000'000u));
  w.num(static_cast<std::uint32_t>(ns % 1'000'000'000u));
  w.str("vehicle");
  const Quat q = quat(c.sensor_roll(), c.sensor_pitch(), c.sensor_yaw());
  for (double v : {c.sensor_x(), c.sensor_y(), c.sensor_z(), q.x, q.y, q.z, q.w}) w.num(v);
  w.num(std::uint32_t{16});
  w.num(std::uint32_t{4});
  const char* names[4] = {"x", "y", "z", "intensity"};
  for (std::uint32_t k = 0; k < 4; ++k) w.str(names[k]), w.num(4 * k), w.num(std::uint32_t{7});  // 7: FLOAT32
  w.num(static_cast<std::uint32_t>(n * 16));
  const std::size_t at = w.out.size();
  w.out.resize(at + n * 16);
  for (std::size_t i = 0; i < n; ++i) {
    const float v[4] = {c.x()[i], c.y()[i], c.z()[i], i < c.intensity().size() ? c.intensity()[i] : 0.0f};
    std::memcpy(w.out.data() + at + 16 * i, v, 16);
  }
  return w;
}

SceneHandler point_cloud(const std::shared_ptr<SceneState>& s, const std::string& topic) {
  const std::uint32_t ch = s->server.add_channel("/lidar/" + topic, "cdr", "foxglove::PointCloud", "omgidl", kPointCloudIdl, true);
  return [s, ch](const void* p, std::uint64_t ns) {
    if (!s->server.wanted(ch)) return;
    const CdrWriter w = foxglove_cloud(*static_cast<const msgs::PointCloud*>(p), ns);
    s->server.publish(ch, ns, reinterpret_cast<const unsigned char*>(w.out.data()), w.out.size());
  };
}

}  // namespace

std::vector<SceneConverterEntry> cloud_converters() {
  return {
      converter<msgs::PointCloud>(point_cloud),
  };
}

}  // namespace brickyard::fw::live_scene
