#pragma once
// A graph's named arguments: "args": {"track": "tracks/IMS.csv", ...} declares each with its
// default; "${track}" anywhere in a string of the graph is replaced by the argument's value, and
// `--arg track=tracks/Monza.csv` gives another. A string that is exactly "${name}" takes the
// value's JSON type (a number, a list of pylons); inside longer text the value must be a string,
// a number or a boolean. Applied before --set, so a --set still has the last word.
#include "graph/diagnostics.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace brickyard::fw {

// Replaces the arguments in `root` (and removes its "args"). Problems go to `d`: --arg not
// "name=value" or naming no declared argument, an argument used but never declared, a non-scalar
// value inside text — each named by the --arg or the file and JSON pointer.
void apply_args(nlohmann::json& root, const std::vector<std::string>& args, const std::string& file, Diagnostics& d);

}  // namespace brickyard::fw
