// What perception sees, in the vehicle frame: /scene/wall (the fitted wall, WallEstimate) and
// /scene/obstacles (ObstacleList, boxes), both foxglove.SceneUpdate.
#include "live/scene_converter.hpp"
#include "live/scene_draw.hpp"

#include <brickyard/msgs/ObstacleList.h>
#include <brickyard/msgs/WallEstimate.h>

#include <algorithm>

namespace brickyard::fw::live_scene {
namespace {

// The wall's polynomial over its extent, at 41 points (none for a wall not seen).
JsonText wall_line(const msgs::WallEstimate& w) {
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
  return lines;
}

SceneHandler wall_estimate(const std::shared_ptr<SceneState>& s, const std::string& topic) {
  return [s, topic](const void* p, std::uint64_t ns) {
    if (!s->server.wanted(s->wall)) return;
    const JsonText lines = wall_line(*static_cast<const msgs::WallEstimate*>(p));
    s->send(s->wall, ns, scene_update(ns, "vehicle", topic, lines, JsonText(), JsonText()));
  };
}

SceneHandler obstacle_list(const std::shared_ptr<SceneState>& s, const std::string& topic) {
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
}

}  // namespace

std::vector<SceneConverterEntry> perception_converters() {
  return {
      converter<msgs::WallEstimate>(wall_estimate),
      converter<msgs::ObstacleList>(obstacle_list),
  };
}

}  // namespace brickyard::fw::live_scene
