#include "live/scene.hpp"

#include "live/json_text.hpp"
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
#include <cmath>
#include <cstring>
#include <mutex>

namespace brickyard::fw {

namespace {
using nlohmann::json;

// The scene's messages are written as JSON text (json_text.hpp), not built as objects.
void stamp(JsonText& w, std::uint64_t ns) {
  w.open('{').key("sec").uint(ns / 1'000'000'000u).key("nsec").uint(ns % 1'000'000'000u).close('}');
}
void vec(JsonText& w, double x, double y, double z) { w.open('{').key("x").num(x).key("y").num(y).key("z").num(z).close('}'); }
struct Quat {
  double x, y, z, w;
};
Quat quat(double roll, double pitch, double yaw) {  // Z-Y-X (yaw, then pitch, then roll)
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy};
}
void quat(JsonText& w, const Quat& q) { w.open('{').key("x").num(q.x).key("y").num(q.y).key("z").num(q.z).key("w").num(q.w).close('}'); }
void pose(JsonText& w, double x, double y, double z, double roll, double pitch, double yaw) {
  w.open('{').key("position");
  vec(w, x, y, z);
  w.key("orientation");
  quat(w, quat(roll, pitch, yaw));
  w.close('}');
}
struct Colour {
  double r, g, b, a = 1.0;
};
void colour(JsonText& w, const Colour& c) { w.open('{').key("r").num(c.r).key("g").num(c.g).key("b").num(c.b).key("a").num(c.a).close('}'); }
// A line's points, x, y and z to the millimetre (a line of thousands of points is most of a
// message's text).
struct Points {
  JsonText text;
  void add(double x, double y, double z) { text.open('{').key("x").num(x, 3).key("y").num(y, 3).key("z").num(z, 3).close('}'); }
};
// One LINE_STRIP primitive, appended to `lines` (an array's items).
void line_strip(JsonText& lines, const Points& pts, double thickness, const Colour& c) {
  lines.open('{').key("type").uint(0).key("pose");
  pose(lines, 0, 0, 0, 0, 0, 0);
  lines.key("thickness").num(thickness).key("scale_invariant").boolean(false).key("points").open('[').raw(pts.text.text()).close(']');
  lines.key("color");
  colour(lines, c);
  lines.key("colors").open('[').close(']').key("indices").open('[').close(']').close('}');
}
// A SceneUpdate of one entity, its lines, cubes and cylinders given as their arrays' items (each
// written by a JsonText of its own; empty: none).
std::string scene_update(std::uint64_t ns, std::string_view frame, std::string_view id, const JsonText& lines, const JsonText& cubes,
                         const JsonText& cylinders) {
  JsonText w;
  w.open('{').key("deletions").open('[').close(']').key("entities").open('[').open('{').key("timestamp");
  stamp(w, ns);
  w.key("frame_id").str(frame).key("id").str(id).key("lifetime");
  stamp(w, 0);
  w.key("frame_locked").boolean(false);
  for (const char* none : {"metadata", "arrows", "spheres", "triangles", "texts", "models"}) w.key(none).open('[').close(']');
  w.key("lines").open('[').raw(lines.text()).close(']');
  w.key("cubes").open('[').raw(cubes.text()).close(']');
  w.key("cylinders").open('[').raw(cylinders.text()).close(']');
  w.close('}').close(']').close('}');
  return w.take();
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
  void send(std::uint32_t ch, std::uint64_t ns, const std::string& text) {
    server.publish(ch, ns, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  }
  // A frame's transform at most every 20 ms of the run (50 Hz; Foxglove interpolates between
  // them): the truth comes at 500 Hz, and a JSON message each was a fifth of the main job's time.
  std::atomic<std::uint64_t> next_truth{0}, next_vehicle{0};
  bool due(std::atomic<std::uint64_t>& next, std::uint64_t ns) {
    if (!server.wanted(tf)) return false;
    std::uint64_t at = next.load();
    return ns >= at && next.compare_exchange_strong(at, ns + 20'000'000);
  }
  void transform(std::uint64_t ns, const char* child, double x, double y, double z, double roll, double pitch, double yaw) {
    JsonText w;
    w.open('{').key("timestamp");
    stamp(w, ns);
    w.key("parent_frame_id").str("map").key("child_frame_id").str(child).key("translation");
    vec(w, x, y, z);
    w.key("rotation");
    quat(w, quat(roll, pitch, yaw));
    w.close('}');
    send(tf, ns, w.text());
  }
  Colour path_colour() {
    std::lock_guard<std::mutex> l(m);
    if (mode == "PATH") return {0.2, 0.9, 0.3};
    if (mode == "WALL_FOLLOW") return {1.0, 0.6, 0.1};
    if (mode == "SAFE_STOP") return {1.0, 0.2, 0.2};
    return {0.9, 0.9, 0.9};
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
      if (truth) s->transform(ns, "truth", v.x(), v.y(), v.z(), v.roll(), v.pitch(), v.yaw());
      if (vehicle) s->transform(ns, "vehicle", v.x(), v.y(), v.z(), v.roll(), v.pitch(), v.yaw());
    };
  if (type == "brickyard::msgs::LocalizationEstimate") {
    s->has_estimate = true;  // (every topic is seen before the run starts)
    return [s](const void* p, std::uint64_t ns) {
      if (!s->due(s->next_vehicle, ns)) return;
      const auto& e = *static_cast<const msgs::LocalizationEstimate*>(p);
      s->transform(ns, "vehicle", e.x(), e.y(), 0, 0, 0, e.yaw());
    };
  }
  if (type == "brickyard::msgs::ModeStatus" && topic.rfind("manager.", 0) == 0)
    return [s](const void* p, std::uint64_t) {
      std::lock_guard<std::mutex> l(s->m);
      s->mode = static_cast<const msgs::ModeStatus*>(p)->mode_name();
    };
  if (type == "brickyard::msgs::TrackMap") {
    // The map comes again and again, the same (for subscribers that join late): its edges are
    // written once and kept while it does not change.
    struct Kept {
      std::mutex m;
      std::vector<double> x, y, left, right;
      JsonText lines;
    };
    auto kept = std::make_shared<Kept>();
    return [s, kept, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->track)) return;
      const auto& m = *static_cast<const msgs::TrackMap*>(p);
      std::string text;
      {
        std::lock_guard<std::mutex> l(kept->m);
        Kept& k = *kept;
        if (k.lines.text().empty() || k.x != m.x() || k.y != m.y() || k.left != m.width_left() || k.right != m.width_right()) {
          k.x = m.x(), k.y = m.y(), k.left = m.width_left(), k.right = m.width_right();
          k.lines = JsonText();
          line_strip(k.lines, edge(m.x(), m.y(), m.width_left(), 1, 0), 0.25, {0.3, 0.6, 1.0});
          line_strip(k.lines, edge(m.x(), m.y(), m.width_right(), -1, 0), 0.25, {0.3, 0.6, 1.0});
        }
        text = scene_update(ns, "map", "map:" + topic, k.lines, JsonText(), JsonText());
      }
      s->send(s->track, ns, text);
    };
  }
  if (type == "brickyard::msgs::TrackWorld") {
    // The simulator's world, read from its bytes by its IDL: the framework is car side and
    // includes no simulator message (architecture.car_side_never_includes_the_simulator).
    struct World {
      explicit World(const std::string& t) : serializer(t), idl(omgidl_schema(idl_text(t) ? idl_text(t) : "")) {}
      SampleSerializer serializer;
      cdr::CdrJson idl;
      std::mutex m;
      std::string bytes;  // the world last drawn, and its drawing: kept while the world is the same
      JsonText lines, cylinders;
    };
    auto w = std::make_shared<World>(type);
    return [s, w, topic, type](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->track)) return;
      std::string text;
      {
        std::lock_guard<std::mutex> l(w->m);
        const auto b = w->serializer.serialize(p);
        const std::string_view now(reinterpret_cast<const char*>(b.data), b.size);
        if (w->bytes.empty() || now != w->bytes) {
          const json d = w->idl.decode(type, b.data, b.size);
          w->bytes.assign(now);
          w->lines = JsonText(), w->cylinders = JsonText();
          const auto x = d["x"].get<std::vector<double>>(), y = d["y"].get<std::vector<double>>();
          for (const auto& [side, sign] : {std::pair<std::string, double>{"left", 1.0}, {"right", -1.0}})
            if (d["wall_" + side].get<bool>())
              line_strip(w->lines, edge(x, y, d["width_" + side].get<std::vector<double>>(), sign, d["wall_" + side + "_offset_m"].get<double>()), 0.4,
                         {0.6, 0.6, 0.6});
          for (const auto& py : d["pylons"]) {
            const double r = py["radius"].get<double>(), h = py["height"].get<double>();
            JsonText& c = w->cylinders;
            c.open('{').key("pose");
            pose(c, py["x"].get<double>(), py["y"].get<double>(), py["z"].get<double>() + h / 2, 0, 0, 0);
            c.key("size");
            vec(c, 2 * r, 2 * r, h);
            c.key("bottom_scale").num(1.0).key("top_scale").num(0.3).key("color");
            colour(c, {1.0, 0.45, 0.0});
            c.close('}');
          }
        }
        text = scene_update(ns, "map", "world:" + topic, w->lines, JsonText(), w->cylinders);
      }
      s->send(s->track, ns, text);
    };
  }
  if (type == "brickyard::msgs::Path")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->path)) return;
      const auto& path = *static_cast<const msgs::Path*>(p);
      Points pts;
      for (const auto& q : path.poses()) pts.add(q.x(), q.y(), 0.1);
      JsonText lines;
      line_strip(lines, pts, 0.3, s->path_colour());
      s->send(s->path, ns, scene_update(ns, "map", topic, lines, JsonText(), JsonText()));
    };
  if (type == "brickyard::msgs::WallEstimate")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->wall)) return;
      const auto& w = *static_cast<const msgs::WallEstimate*>(p);
      JsonText lines;
      if (w.valid() && !w.coefficients().empty() && w.x_max() > w.x_min()) {
        Points pts;
        for (int i = 0; i <= 40; ++i) {
          const double x = w.x_min() + (w.x_max() - w.x_min()) * i / 40.0;
          double y = 0, xp = 1;
          for (double c : w.coefficients()) y += c * xp, xp *= x;
          pts.add(x, y, 0.5);
        }
        line_strip(lines, pts, 0.2, {1.0, 0.9, 0.2});
      }
      s->send(s->wall, ns, scene_update(ns, "vehicle", topic, lines, JsonText(), JsonText()));
    };
  if (type == "brickyard::msgs::ObstacleList")
    return [s, topic](const void* p, std::uint64_t ns) {
      if (!s->server.wanted(s->obstacles)) return;
      const auto& list = *static_cast<const msgs::ObstacleList*>(p);
      JsonText cubes;
      for (const auto& o : list.obstacles()) {
        cubes.open('{').key("pose");
        pose(cubes, o.x(), o.y(), o.z(), 0, 0, 0);
        cubes.key("size");
        vec(cubes, std::max(o.size_x(), 0.2), std::max(o.size_y(), 0.2), std::max(o.size_z(), 0.2));
        cubes.key("color");
        colour(cubes, {1.0, 0.2, 0.6, 0.8});
        cubes.close('}');
      }
      s->send(s->obstacles, ns, scene_update(ns, "vehicle", topic, JsonText(), cubes, JsonText()));
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
      s->server.publish(ch, ns, reinterpret_cast<const unsigned char*>(w.out.data()), w.out.size());
    };
  }
  return {};
}

}  // namespace brickyard::fw
