#pragma once
#include "cli/arguments.hpp"
#include "graph/graph.hpp"
#include "loader/registry.hpp"

namespace brickyard::fw::cli {

// The plugins of every folder in search order (--plugin-path first, then the graph's own
// "plugin_path" when g is given); an earlier folder's plugin overrides a later one of the same
// name, and says so on stderr (not with --quiet).
Registry load_registry(const Args& a, const GraphDecl* g);

}  // namespace brickyard::fw::cli
