#pragma once
// `brickyard bag play RECORDING`: republishes a recording's topics over DDS, under their own
// names (NODE.PORT) and types, at the recorded times (`--rate X`: X times as fast), for another
// process to subscribe: a graph run with `--process`, `brickyard topic echo`, any DDS reader.
// (Into a graph of the same process, the replay plugins do it: docs/recording.md.)
#include <string>
#include <vector>

namespace brickyard::fw {

struct BagPlayOptions {
  std::string file;
  int domain = 0;
  std::string security, identity;  // --security DIR (--identity NAME): join a secured graph as that identity
  bool ros2_naming = false;        // --naming ros2: play onto topics named as ROS 2 names them
  double rate = 1.0;
  std::vector<std::string> only;  // NODE.PORT patterns ('*' any); empty: every topic
  double preroll_s = 1.0;         // for readers elsewhere to match the new writers
  std::string map;                // --map FILE: a ROS 2 bag (not a Brickyard recording), its topics onto wires (cli/bag_map.hpp)
};

// 0 played through; 1 interrupted; 2 the file is not a recording, is damaged, or holds a type
// this build does not know (named); with --map, the map is wrong or names what the bag lacks.
int bag_play(const BagPlayOptions& o);

}  // namespace brickyard::fw
