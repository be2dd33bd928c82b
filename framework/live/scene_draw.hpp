#pragma once
// Foxglove's scene schemas written as JSON text (json_text.hpp), not built as objects: the pieces
// the live scene's converters (scene_*.cpp) draw with. Frames, poses and colours as Foxglove
// names them (foxglove.FrameTransform, foxglove.SceneUpdate).
#include "live/json_text.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::fw::live_scene {

inline void stamp(JsonText& w, std::uint64_t ns) {
  w.open('{').key("sec").uint(ns / 1'000'000'000u).key("nsec").uint(ns % 1'000'000'000u).close('}');
}
inline void vec(JsonText& w, double x, double y, double z) { w.open('{').key("x").num(x).key("y").num(y).key("z").num(z).close('}'); }

struct Quat {
  double x, y, z, w;
};
inline Quat quat(double roll, double pitch, double yaw) {  // Z-Y-X (yaw, then pitch, then roll)
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy};
}
inline void quat(JsonText& w, const Quat& q) {
  w.open('{').key("x").num(q.x).key("y").num(q.y).key("z").num(q.z).key("w").num(q.w).close('}');
}
inline void pose(JsonText& w, double x, double y, double z, double roll, double pitch, double yaw) {
  w.open('{').key("position");
  vec(w, x, y, z);
  w.key("orientation");
  quat(w, quat(roll, pitch, yaw));
  w.close('}');
}

struct Colour {
  double r, g, b, a = 1.0;
};
inline void colour(JsonText& w, const Colour& c) {
  w.open('{').key("r").num(c.r).key("g").num(c.g).key("b").num(c.b).key("a").num(c.a).close('}');
}

// A line's points, x, y and z to the millimetre (a line of thousands of points is most of a
// message's text).
struct Points {
  JsonText text;
  void add(double x, double y, double z) { text.open('{').key("x").num(x, 3).key("y").num(y, 3).key("z").num(z, 3).close('}'); }
};

// One LINE_STRIP primitive, appended to `lines` (an array's items).
void line_strip(JsonText& lines, const Points& pts, double thickness, const Colour& c);

// A SceneUpdate of one entity, its lines, cubes and cylinders given as their arrays' items (each
// written by a JsonText of its own; empty: none).
std::string scene_update(std::uint64_t ns, std::string_view frame, std::string_view id, const JsonText& lines, const JsonText& cubes,
                         const JsonText& cylinders);

// The closed polyline `width + beyond` to the left of the centre line (sign -1: the right), z = 0.
Points edge(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& width, double sign, double beyond);

}  // namespace brickyard::fw::live_scene
