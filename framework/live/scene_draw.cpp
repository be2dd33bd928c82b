#include "live/scene_draw.hpp"

#include <algorithm>

namespace brickyard::fw::live_scene {

void line_strip(JsonText& lines, const Points& pts, double thickness, const Colour& c) {
  lines.open('{').key("type").uint(0).key("pose");
  pose(lines, 0, 0, 0, 0, 0, 0);
  lines.key("thickness").num(thickness).key("scale_invariant").boolean(false).key("points").open('[').raw(pts.text.text()).close(']');
  lines.key("color");
  colour(lines, c);
  lines.key("colors").open('[').close(']').key("indices").open('[').close(']').close('}');
}

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

}  // namespace brickyard::fw::live_scene
