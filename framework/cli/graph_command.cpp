// `brickyard graph GRAPH.json --dot`: the graph, resolved against the plugins found, for Graphviz.
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/load_registry.hpp"
#include "graph/resolve.hpp"

#include <iostream>

namespace brickyard::fw::cli {

int cmd_graph(const Args& a) {
  if (a.target.empty()) usage_error("graph", "needs a graph file");
  if (!a.dot) usage_error("graph", "choose an output format: --dot");
  GraphDecl g = load_graph_file(a.target, a.sets, a.args);
  Registry reg = load_registry(a, &g);
  resolve_graph(g, reg);
  std::cout << graph_dot(g, &reg);
  return 0;
}

}  // namespace brickyard::fw::cli
