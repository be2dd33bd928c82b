// `brickyard plugins [NAME] [--json]`: every plugin found, or with a NAME only that one (exit 2
// naming the known ones when none has it); a library that failed to load is an error (exit 2).
#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/load_registry.hpp"

#include <cstdio>
#include <iostream>

namespace brickyard::fw::cli {

int cmd_plugins(const Args& a) {
  Registry reg = load_registry(a, nullptr);
  std::vector<const PluginEntry*> shown;
  for (const auto& p : reg.plugins())
    if (a.target.empty() || p.manifest.name == a.target) shown.push_back(&p);
  if (!a.target.empty() && shown.empty()) {
    std::string known;
    for (const auto& p : reg.plugins()) known += (known.empty() ? "" : ", ") + p.manifest.name;
    std::fprintf(stderr, "error: plugins %s: no plugin of that name (known: %s)\n", a.target.c_str(), known.c_str());
    return 2;
  }
  if (a.json) {
    nlohmann::json j;
    j["plugins"] = nlohmann::json::array();
    for (const auto* p : shown) j["plugins"].push_back(manifest_to_json(*p));
    j["errors"] = nlohmann::json::array();
    for (const auto& lp : reg.problems()) j["errors"].push_back({{"library", lp.library}, {"problems", lp.problems}});
    std::cout << j.dump(2) << "\n";
  } else {
    for (const auto* p : shown) std::cout << plugin_text(*p);
  }
  for (const auto& lp : reg.problems())
    for (const auto& p : lp.problems) std::fprintf(stderr, "error: %s: %s\n", lp.library.c_str(), p.c_str());
  return reg.problems().empty() ? 0 : 2;
}

}  // namespace brickyard::fw::cli
