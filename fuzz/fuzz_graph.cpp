// libFuzzer harness: a graph file's text through the parser and its checks (JSON with positions,
// "args", "include", every section), as `brickyard validate` reads one. Bad input must end in
// InvalidInput naming its place, never a crash, a hang or unbounded memory.
#include "graph/diagnostics.hpp"
#include "graph/graph.hpp"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto g = brickyard::fw::parse_graph_text(text, "fuzz.json", {"n.p=1"}, {});
    (void)g;
  } catch (const brickyard::fw::InvalidInput&) {
  }
  return 0;
}
