// libFuzzer harness: a road-graph file (brickyard-plan graph's binary format, docs/planning.md)
// through RoadGraph::load, as planning.road_graph loads one. Bad input must end in a
// runtime_error naming the file and what is wrong, never a crash or an allocation it cannot make.
#include "fuzz_input.hpp"
#include "planning/common/road_graph.hpp"

#include <cstdint>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = brickyard::fuzz::as_file(data, size, ".roadgraph");
  try {
    const auto g = brickyard::planning::RoadGraph::load(path);
    (void)g.node_count();
  } catch (const std::exception&) {
  }
  return 0;
}
