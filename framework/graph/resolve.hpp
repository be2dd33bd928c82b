#pragma once
// A graph checked against the plugins' manifests: every error the user can fix, before any
// plugin object exists.
#include "graph/diagnostics.hpp"
#include "graph/graph.hpp"
#include "loader/registry.hpp"

#include <functional>
#include <map>
#include <set>

namespace brickyard::fw {

// The step deadline a node gets when neither its graph node nor its plugin sets one: this many of
// the periods its steps come at, at least the floor; the last when no period is known.
inline constexpr double kDefaultDeadlinePeriods = 10, kDefaultDeadlineFloor_s = 0.5, kDefaultDeadlineUnknown_s = 2.0;
// On the sim clock a deadline the graph did not set only ends a step stuck this long (a slow
// step must not change a run's result: runs are reproducible bit for bit on any machine).
inline constexpr double kSimHang_s = 30.0;
// A lifecycle call (construction, configure, activate, deactivate) stuck this long ends the
// process naming the node: a map read and prepared, a road graph built, a file written take
// seconds (tens under the sanitizers), never a minute.
inline constexpr double kLifecycleHang_s = 60.0;

struct ResolvedNode {
  const NodeDecl* decl = nullptr;
  const PluginEntry* plugin = nullptr;
  Params params;
  std::int64_t period_ns = 0;             // 0: no periodic trigger
  std::set<std::string> trigger_inputs;   // inputs whose arrival steps the node
  std::int64_t latency_ns = 0;            // sim clock: a step's outputs delivered this long after it
  double deadline_s = 0;                  // the step deadline: the graph node's deadline_s, else the manifest's parameter,
                                          // else derived from the trigger (deadline_derived)
  bool deadline_derived = false;          // neither the graph nor the plugin set it
  bool deadline_by_graph = false;         // the graph set it (deadline_s, or the plugin's parameter): held on the sim
                                          // clock too; any other only ends a hang there (kSimHang_s)
  std::size_t order = 0;                  // position in the deterministic schedule order
  bool here = true;                       // runs in this process (a split run on the sim clock keeps every node:
                                          // the others' as phantoms, exec/lockstep.hpp)
};

struct ResolvedGraph {
  const GraphDecl* decl = nullptr;
  std::vector<ResolvedNode> nodes;        // in schedule order: upstream first, then by name (this process's,
                                          // or with `lockstep` every process's, `here` telling them apart)
  bool lockstep = false;                  // one process of a split graph on the sim clock (exec/lockstep.hpp)
  std::set<std::string> processes;
  std::vector<std::string> notices;       // said before the run (not with --quiet): params a plugin swap left out
  std::map<std::string, std::string> wire_types;  // "node.input" -> the type its writer sends, every process's
  std::map<std::string, std::string> output_types;  // "node.output" of any type -> the type its readers take

  const ResolvedNode* node(const std::string& name) const;
};

// The plugins' own checks of their nodes (Manifest::check; the host's are exec/node_checks.hpp).
using NodeChecks = std::function<std::vector<Diagnostic>(const ResolvedGraph&)>;

// `process`: empty to run every node here; else only that process's nodes (checked to exist), or
// on the sim clock every node, the others' marked not `here` (the lockstep). When the graph has
// errors, `checks` run too on every node that resolved without one of its own, and what they
// find is thrown with the rest: validation says everything in one pass. (On a graph without
// errors the caller runs them on the graph returned.)
ResolvedGraph resolve_graph(const GraphDecl& g, const Registry& reg, const std::string& process = {}, const NodeChecks& checks = {});

// Convert one JSON param value against its spec; returns an error text or empty.
std::string convert_param(const ParamSpec& spec, const nlohmann::json& v, ParamValue& out);

}  // namespace brickyard::fw
