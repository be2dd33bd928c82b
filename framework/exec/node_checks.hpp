#pragma once
// Each plugin's own checks (Manifest::check, ABI 2.4), run on a resolved graph before any plugin
// object exists: by `brickyard validate` and before a run starts.
#include "graph/diagnostics.hpp"
#include "graph/resolve.hpp"

#include <string>
#include <vector>

namespace brickyard::fw {

// Every node's failed check: where "node 'N' (plugin)", what "... (file#pointer)"; empty when all pass.
std::vector<Diagnostic> run_node_checks(const ResolvedGraph& rg);

// A plugin's "parameter 'expect' /0/field: ..." (a parameter, and a JSON pointer inside its
// value) said with the file and pointer that gave the value: "... (g.json#/nodes/check/params/expect/0/field)".
std::string with_param_place(const GraphDecl& g, const std::string& node, const std::string& what);

}  // namespace brickyard::fw
