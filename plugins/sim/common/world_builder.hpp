#pragma once
// The simulator's world from the world node's settings: the road banked, the walls on their sides
// (the outer one on the outside of the loop unless the graph says which), the pylons from their
// JSON list; and which pylons stand off the road. Framework-free.
#include "track.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::sim {

// The simulator's road is banked in its turns by default (IMS: 9 deg 12 min), unlike the map's.
BankSpec default_bank();

struct WallSettings {
  std::string outer_side = "auto";  // left, right, or auto: the outside of the loop
  bool outer_wall = true;
  double outer_wall_offset_m = 0.0;  // beyond the track edge
  bool inner_wall = false;
  double inner_wall_offset_m = 2.0, wall_height_m = 1.2;
};

// Walls as the settings place them along `line`.
Walls place_walls(const CenterLine& line, const WallSettings& s);

// A world that cannot be built as configured; the message names the parameter at fault.
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Pylons from the JSON array of the `pylons` parameter ({s, d, radius, height} objects, s and d
// required). Throws WorldError naming the JSON pointer at fault.
std::vector<Pylon> parse_pylons(const std::string& json_text);

// The world on `line` named `name`: banked by `bank`, walled by `walls`, with the pylons of
// `pylons_json`. Throws WorldError for a bank or a pylon list that does not fit.
WorldSpec build_world(CenterLine line, std::string name, const BankSpec& bank, const WallSettings& walls,
                      const std::string& pylons_json);

// The pylons that stand off the road (beyond its left or right edge where they stand).
std::vector<Pylon> pylons_off_road(const Track& track);

}  // namespace brickyard::sim
