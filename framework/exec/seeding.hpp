#pragma once
// A node's seed (Context::seed): the run's --seed mixed with the node's name, so that adding a
// node to a graph does not change another node's noise.
#include "math/fnv1a.hpp"

#include <cstdint>
#include <string_view>

namespace brickyard::fw {

namespace seeding {
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
}  // namespace seeding

inline std::uint64_t node_seed(std::uint64_t run_seed, std::string_view node) {
  return seeding::splitmix64(run_seed ^ math::fnv1a(node));
}

}  // namespace brickyard::fw
