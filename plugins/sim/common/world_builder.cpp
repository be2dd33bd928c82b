#include "world_builder.hpp"

#include <nlohmann/json.hpp>

namespace brickyard::sim {

BankSpec default_bank() {
  BankSpec b;
  b.mode = "curvature";
  b.degrees = 9.2;
  return b;
}

Walls place_walls(const CenterLine& line, const WallSettings& s) {
  Walls walls;
  std::string outer = s.outer_side;
  if (outer == "auto") outer = counter_clockwise(line) ? "right" : "left";
  const bool outer_left = outer == "left";
  walls.height = s.wall_height_m;
  auto set_side = [&](bool left, bool on, double off) {
    (left ? walls.left : walls.right) = on;
    (left ? walls.left_offset : walls.right_offset) = off;
  };
  set_side(outer_left, s.outer_wall, s.outer_wall_offset_m);
  set_side(!outer_left, s.inner_wall, s.inner_wall_offset_m);
  return walls;
}

std::vector<Pylon> parse_pylons(const std::string& text) {
  auto j = nlohmann::json::parse(text);
  if (!j.is_array()) throw WorldError("parameter 'pylons': must be an array");
  std::vector<Pylon> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string at = "parameter 'pylons' /" + std::to_string(i);
    if (!j[i].is_object()) throw WorldError(at + ": must be an object {s, d, radius, height}");
    Pylon p;
    for (auto it = j[i].begin(); it != j[i].end(); ++it) {
      if (!it->is_number()) throw WorldError(at + "/" + it.key() + ": must be a number");
      double v = it->get<double>();
      if (it.key() == "s") p.s = v;
      else if (it.key() == "d") p.d = v;
      else if (it.key() == "radius") p.radius = v;
      else if (it.key() == "height") p.height = v;
      else throw WorldError(at + "/" + it.key() + ": unknown key (s, d, radius, height)");
    }
    if (!j[i].contains("s") || !j[i].contains("d")) throw WorldError(at + ": needs s and d");
    if (p.radius <= 0 || p.height <= 0) throw WorldError(at + ": radius and height must be positive");
    out.push_back(p);
  }
  return out;
}

WorldSpec build_world(CenterLine line, std::string name, const BankSpec& bank, const WallSettings& walls,
                      const std::string& pylons_json) {
  WorldSpec w;
  w.line = std::move(line);
  w.name = std::move(name);
  try {
    w.bank = bank_profile(w.line, bank);
  } catch (const std::invalid_argument& e) {
    throw WorldError(std::string("parameter 'bank_mode': ") + e.what());
  }
  w.walls = place_walls(w.line, walls);
  w.pylons = parse_pylons(pylons_json);
  return w;
}

std::vector<Pylon> pylons_off_road(const Track& track) {
  std::vector<Pylon> off;
  for (const auto& q : track.spec().pylons) {
    Frenet f = track.at(q.s, q.d);
    if (q.d > track.width_left(f.seg, f.u) || q.d < -track.width_right(f.seg, f.u)) off.push_back(q);
  }
  return off;
}

}  // namespace brickyard::sim
