// /scene/track (foxglove.SceneUpdate): the car's map's edges (TrackMap) and the simulator's
// walls and pylons (TrackWorld). Both come again and again, the same (for subscribers that join
// late): each is drawn once and its drawing kept while it does not change.
#include "live/scene_converter.hpp"
#include "live/scene_draw.hpp"
#include "cdr/cdr_json.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"

#include <brickyard/msgs/TrackMap.h>

#include <nlohmann/json.hpp>

namespace brickyard::fw::live_scene {
namespace {
using nlohmann::json;

struct KeptMap {
  std::mutex m;
  std::vector<double> x, y, left, right;
  JsonText lines;
};

SceneHandler track_map(const std::shared_ptr<SceneState>& s, const std::string& topic) {
  auto kept = std::make_shared<KeptMap>();
  return [s, kept, topic](const void* p, std::uint64_t ns) {
    if (!s->server.wanted(s->track)) return;
    const auto& m = *static_cast<const msgs::TrackMap*>(p);
    std::string text;
    {
      std::lock_guard<std::mutex> l(kept->m);
      KeptMap& k = *kept;
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

// The simulator's world, read from its bytes by its IDL: the framework is car side and
// includes no simulator message (architecture.car_side_never_includes_the_simulator); its type
// is known by name alone (message_traits).
struct KeptWorld {
  explicit KeptWorld(const std::string& t) : serializer(t), idl(omgidl_schema(idl_text(t) ? idl_text(t) : "")) {}
  SampleSerializer serializer;
  cdr::CdrJson idl;
  std::mutex m;
  std::string bytes;  // the world last drawn, and its drawing: kept while the world is the same
  JsonText lines, cylinders;
};

void pylon(JsonText& c, const json& py) {
  const double r = py["radius"].get<double>(), h = py["height"].get<double>();
  c.open('{').key("pose");
  pose(c, py["x"].get<double>(), py["y"].get<double>(), py["z"].get<double>() + h / 2, 0, 0, 0);
  c.key("size");
  vec(c, 2 * r, 2 * r, h);
  c.key("bottom_scale").num(1.0).key("top_scale").num(0.3).key("color");
  colour(c, {1.0, 0.45, 0.0});
  c.close('}');
}

// The world's walls (each side the simulator has one) and its pylons, into `w`'s drawing.
void draw_world(KeptWorld& w, const json& d) {
  w.lines = JsonText(), w.cylinders = JsonText();
  const auto x = d["x"].get<std::vector<double>>(), y = d["y"].get<std::vector<double>>();
  for (const auto& [side, sign] : {std::pair<std::string, double>{"left", 1.0}, {"right", -1.0}})
    if (d["wall_" + side].get<bool>())
      line_strip(w.lines, edge(x, y, d["width_" + side].get<std::vector<double>>(), sign, d["wall_" + side + "_offset_m"].get<double>()),
                 0.4, {0.6, 0.6, 0.6});
  for (const auto& py : d["pylons"]) pylon(w.cylinders, py);
}

SceneHandler track_world(const std::shared_ptr<SceneState>& s, const std::string& topic) {
  const std::string type = message_traits<msgs::TrackWorld>::name;
  auto w = std::make_shared<KeptWorld>(type);
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
        draw_world(*w, d);
      }
      text = scene_update(ns, "map", "world:" + topic, w->lines, JsonText(), w->cylinders);
    }
    s->send(s->track, ns, text);
  };
}

}  // namespace

std::vector<SceneConverterEntry> track_converters() {
  return {
      converter<msgs::TrackMap>(track_map),
      converter<msgs::TrackWorld>(track_world),
  };
}

}  // namespace brickyard::fw::live_scene
