#include "live/scene.hpp"

#include "live/live_server.hpp"
#include "cdr/cdr_json.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"

#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/ModeStatus.h>
#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/msgs/TrackMap.h>
#include <brickyard/msgs/VehicleState.h>
#include <brickyard/msgs/WallEstimate.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <charconv>
#include <cmath>
#include <cstring>
#include <mutex>

namespace brickyard::fw {

namespace {
using nlohmann::json;

json stamp(std::uint64_t ns) { return {{"sec", ns / 1'000'000'000u}, {"nsec", ns % 1'000'000'000u}}; }
json vec(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
json quat(double roll, double pitch, double yaw) {  // Z-Y-X (yaw, then pitch, then roll)
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {{"x", sr * cp * cy - cr * sp * sy}, {"y", cr * sp * cy + sr * cp * sy}, {"z", cr * cp * sy - sr * sp * cy}, {"w", cr * cp * cy + sr * sp * sy}};
}
json pose(double x, double y, double z, double roll, double pitch, double yaw) {
  return {{"position", vec(x, y, z)}, {"orientation", quat(roll, pitch, yaw)}};
}
json colour(double r, double g, double b, double a = 1.0) { return {{"r", r}, {"g", g}, {"b", b}, {"a", a}}; }
// A line's points as JSON text, written directly: nlohmann builds an object per point, which for
// the map's edges and the path took a fifth of the main job's time. In the message the line holds
// a placeholder string, replaced by the text after the dump (Message::text).
struct Points {
  std::string text = "[";
  void add(double x, double y, double z) {
    char b[160];
    char* p = b;
    if (text.size() > 1) *p++ = ',';
    for (const auto& [key, value] : {std::pair<const char*, double>{"{\"x\":", x}, {",\"y\":", y}, {",\"z\":", z}}) {
      // JSON has no NaN or infinity, and a diverging fit is no place to draw: 0 there.
      const double v = std::isfinite(value) && std::fabs(value) < 1e9 ? value : 0.0;
      for (const char* k = key; *k;) *p++ = *k++;
      p = std::to_chars(p, b + sizeof b - 2, v, std::chars_format::fixed, 3).ptr;  // |v| < 1e9: at most 14 characters
    }
    *p++ = '}';
    text.append(b, p);
  }
};
struct Message {
  json j;
  std::vector<std::string> points;
  std::string dump() const {
    std::string s = j.dump();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string key = "\"@points" + std::to_string(i) + "@\"";
      const auto at = s.find(key);
      if (at != std::string::npos) s.replace(at, key.size(), points[i] + "]");
    }
    return s;
  }
};
json line_strip(Message& m, Points pts, double thickness, const json& c) {
  m.points.push_back(std::move(pts.text));
  return {{"type", 0}, {"pose", pose(0, 0, 0, 0, 0, 0)}, {"thickness", thickness}, {"scale_invariant", false},
          {"points", "@points" + std::to_string(m.points.size() - 1) + "@"}, {"color", c}, {"colors", json::array()},
          {"indices", json::array()}};
}
json entity(std::uint64_t ns, const std::string& frame, const std::string& id) {
  return {{"timestamp", stamp(ns)}, {"frame_id", frame}, {"id", id}, {"lifetime", stamp(0)}, {"frame_locked", false},
          {"metadata", json::array()}, {"arrows", json::array()}, {"cubes", json::array()}, {"spheres", json::array()},
          {"cylinders", json::array()}, {"lines", json::array()}, {"triangles", json::array()}, {"texts", json::array()},
          {"models", json::array()}};
}
// The closed polyline `width + beyond` to the left of the centre line (sign -1: the right), z = 0.
Points edge(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& width, double sign, double beyond) {
  Points pts;
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t i = 0; i <= n && n > 1; ++i) {
    const std::size_t k = i % n, a = (k + n - 1) % n, b = (k + 1) % n;
    double tx = x[b] - x[a], ty = y[b] - y[a];
    const double len = std::hypot(tx, ty);
    if (len <= 0) continue;
    tx /= len, ty /= len;
    const double w = (k < width.size() ? width[k] : 0.0) + beyond;
    pts.add(x[k] - sign * ty * w, y[k] + sign * tx * w, 0);
  }
  return pts;
}
const char* kSchema = R"({"type":"object"})";  // Foxglove knows its schemas by name

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
}  // namespace

struct LiveScene::Impl {
  LiveServer& server;
  std::uint32_t tf = 0, track = 0, path = 0, wall = 0, obstacles = 0;
  bool has_estimate = false;
  std::mutex m;
  std::string mode;  // the system manager's, for the path's colour

  explicit Impl(LiveServer& s) : server(s) {}
  std::uint32_t channel(const std::string& topic, const std::string& schema) {
    return server.add_channel(topic, "json", schema, "jsonschema", kSchema);
  }
  void send(std::uint32_t ch, std::uint64_t ns, const json& j) { send_message(ch, ns, Message{j, {}}); }
  void send_message(std::uint32_t ch, std::uint64_t ns, const Message& m) {
    const std::string s = m.dump();
    server.publish(ch, ns, reinterpret_cast<const unsigned char*>(s.data()), s.size());
  }
  // A frame's transform at most every 20 ms of the run (50 Hz; Foxglove interpolates between
  // them): the truth comes at 500 Hz, and a JSON message each was a fifth of the main job's time.
  std::atomic<std::uint64_t> next_truth{0}, next_vehicle{0};
  bool due(std::atomic<std::uint64_t>& next, std::uint64_t ns) {
    if (!server.wanted(tf)) return false;
    std::uint64_t at = next.load();
    return ns >= at && next.compare_exchange_strong(at, ns + 20'000'000);
  }
  void transform(std::uint64_t ns, const std::string& child, const json& p) {
    send(tf, ns, {{"timestamp", stamp(ns)}, {"parent_frame_id", "map"}, {"child_frame_id", child},
                  {"translation", p["position"]}, {"rotation", p["orientation"]}});
  }
  json path_colour() {
    std::lock_guard<std::mutex> l(m);
    if (mode == "PATH") return colour(0.2, 0.9, 0.3);
    if (mode == "WALL_FOLLOW") return colour(1.0, 0.6, 0.1);
    if (mode == "SAFE_STOP") return colour(1.0, 0.2, 0.2);
    return colour(0.9, 0.9, 0.9);
  }
};

LiveScene::LiveScene(LiveServer& server) : impl_(std::make_shared<Impl>(server)) {
  Impl& s = *impl_;
  s.tf = s.channel("/tf", "foxglove.FrameTransform");
  s.track = s.channel("/scene/track", "foxglove.SceneUpdate");
  s.path = s.channel("/scene/path", "foxglove.SceneUpdate");
  s.wall = s.channel("/scene/wall", "foxglove.SceneUpdate");
  s.obstacles = s.channel("/scene/obstacles", "foxglove.SceneUpdate");
}

LiveScene::~LiveScene() = default;

std::function<void(const void*, std::uint64_t)> LiveScene::handler(const std::string& topic, const std::string& type) {
  auto s = impl_;
  if (type == "brickyard::msgs::VehicleState")
    return [s](const void* p, std::uint64_t ns) {
      const auto& v = *static_cast<const msgs::VehicleState*>(p);
      const bool truth = s->due(s->next_truth, ns), vehicle = !s->has_estimate && s->due(s->next_vehicle, ns);
      if (!truth && !vehicle) return;
      const json at = pose(v.x(), v.y(), v.z(), v.roll(), v.pitch(), v.yaw());
      if (truth) s->transform(ns, "truth", at);
      if (vehicle) s->transform(ns, "vehicle", at);
    };
  if (type == "brickyard::msgs::LocalizationEstimate") {
    s->has_estimate = true;  // (every topic is seen before the run starts)
    return [s](const void* p, std::uint64_t ns) {
      if (!s->due(s->next_vehicle, ns)) return;
      const auto& e = *static_cast<const msgs::LocalizationEstimate*>(p);
      s->transform(ns, "vehicle", pose(e.x(), e.y(), 0, 0, 0, e.yaw()));
    };
  }
  if (type == "brickyard::msgs::ModeStatus" && topic.rfind("manager.", 0) == 0)
    return [s](const void* p, std::uint64_t) {
      std::lock_guard<std::mutex> l(s->m);
      s->mode = static_cast<const msgs::ModeStatus*>(p)->mode_name();
    };
  if (type == "brickyard::msgs::TrackMap")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->track)) return;
      const auto& m = *static_cast<const msgs::TrackMap*>(p);
      Message msg;
      json e = entity(ns, "map", "map:" + topic);
      e["lines"].push_back(line_strip(msg, edge(m.x(), m.y(), m.width_left(), 1, 0), 0.25, colour(0.3, 0.6, 1.0)));
      e["lines"].push_back(line_strip(msg, edge(m.x(), m.y(), m.width_right(), -1, 0), 0.25, colour(0.3, 0.6, 1.0)));
      msg.j = {{"deletions", json::array()}, {"entities", {e}}};
      s->send_message(s->track, ns, msg);
    };
  if (type == "brickyard::msgs::TrackWorld") {
    // The simulator's world, read from its bytes by its IDL: the framework is car side and
    // includes no simulator message (architecture.car_side_never_includes_the_simulator).
    struct World {
      explicit World(const std::string& t) : serializer(t), idl(omgidl_schema(idl_text(t) ? idl_text(t) : "")) {}
      SampleSerializer serializer;
      cdr::CdrJson idl;
      std::mutex m;
    };
    auto w = std::make_shared<World>(type);
    return [s, w, topic, type](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->track)) return;
      json d;
      {
        std::lock_guard<std::mutex> l(w->m);
        const auto b = w->serializer.serialize(p);
        d = w->idl.decode(type, b.data, b.size);
      }
      const auto x = d["x"].get<std::vector<double>>(), y = d["y"].get<std::vector<double>>();
      Message msg;
      json e = entity(ns, "map", "world:" + topic);
      for (const auto& [side, sign] : {std::pair<std::string, double>{"left", 1.0}, {"right", -1.0}})
        if (d["wall_" + side].get<bool>())
          e["lines"].push_back(line_strip(msg, edge(x, y, d["width_" + side].get<std::vector<double>>(), sign, d["wall_" + side + "_offset_m"].get<double>()),
                                          0.4, colour(0.6, 0.6, 0.6)));
      for (const auto& py : d["pylons"]) {
        const double r = py["radius"].get<double>(), h = py["height"].get<double>();
        e["cylinders"].push_back({{"pose", pose(py["x"].get<double>(), py["y"].get<double>(), py["z"].get<double>() + h / 2, 0, 0, 0)},
                                  {"size", vec(2 * r, 2 * r, h)}, {"bottom_scale", 1}, {"top_scale", 0.3}, {"color", colour(1.0, 0.45, 0.0)}});
      }
      msg.j = {{"deletions", json::array()}, {"entities", {e}}};
      s->send_message(s->track, ns, msg);
    };
  }
  if (type == "brickyard::msgs::Path")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->path)) return;
      const auto& path = *static_cast<const msgs::Path*>(p);
      Points pts;
      for (const auto& q : path.poses()) pts.add(q.x(), q.y(), 0.1);
      Message msg;
      json e = entity(ns, "map", topic);
      e["lines"].push_back(line_strip(msg, std::move(pts), 0.3, s->path_colour()));
      msg.j = {{"deletions", json::array()}, {"entities", {e}}};
      s->send_message(s->path, ns, msg);
    };
  if (type == "brickyard::msgs::WallEstimate")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->wall)) return;
      const auto& w = *static_cast<const msgs::WallEstimate*>(p);
      Message msg;
      json e = entity(ns, "vehicle", topic);
      if (w.valid() && !w.coefficients().empty() && w.x_max() > w.x_min()) {
        Points pts;
        for (int i = 0; i <= 40; ++i) {
          const double x = w.x_min() + (w.x_max() - w.x_min()) * i / 40.0;
          double y = 0, xp = 1;
          for (double c : w.coefficients()) y += c * xp, xp *= x;
          pts.add(x, y, 0.5);
        }
        e["lines"].push_back(line_strip(msg, std::move(pts), 0.2, colour(1.0, 0.9, 0.2)));
      }
      msg.j = {{"deletions", json::array()}, {"entities", {e}}};
      s->send_message(s->wall, ns, msg);
    };
  if (type == "brickyard::msgs::ObstacleList")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->obstacles)) return;
      const auto& list = *static_cast<const msgs::ObstacleList*>(p);
      json e = entity(ns, "vehicle", topic);
      for (const auto& o : list.obstacles())
        e["cubes"].push_back({{"pose", pose(o.x(), o.y(), o.z(), 0, 0, 0)},
                              {"size", vec(std::max(o.size_x(), 0.2), std::max(o.size_y(), 0.2), std::max(o.size_z(), 0.2))},
                              {"color", colour(1.0, 0.2, 0.6, 0.8)}});
      s->send(s->obstacles, ns, {{"deletions", json::array()}, {"entities", {e}}});
    };
  if (type == "brickyard::msgs::PointCloud") {
    const std::uint32_t ch = s->server.add_channel("/lidar/" + topic, "cdr", "foxglove::PointCloud", "omgidl", kPointCloudIdl, true);
    return [s, ch](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(ch)) return;
      const auto& c = *static_cast<const msgs::PointCloud*>(p);
      const std::size_t n = std::min({c.x().size(), c.y().size(), c.z().size()});
      CdrWriter w;
      w.num(static_cast<std::uint32_t>(ns / 1'000'000'000u));
      w.num(static_cast<std::uint32_t>(ns % 1'000'000'000u));
      w.str("vehicle");
      const json q = quat(c.sensor_roll(), c.sensor_pitch(), c.sensor_yaw());
      for (double v : {c.sensor_x(), c.sensor_y(), c.sensor_z(), q["x"].get<double>(), q["y"].get<double>(), q["z"].get<double>(),
                       q["w"].get<double>()})
        w.num(v);
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
      s->server.publish(ch, ns, reinterpret_cast<const unsigned char*>(w.out.data()), w.out.size());
    };
  }
  return {};
}

}  // namespace brickyard::fw
