#include "cli/load_registry.hpp"

#include <cstdio>

namespace brickyard::fw::cli {

Registry load_registry(const Args& a, const GraphDecl* g) {
  Registry reg;
  for (const auto& d : plugin_search_dirs(a.plugin_paths, g ? g->plugin_path : std::vector<std::string>{})) reg.add_directory(d);
  if (!a.quiet)
    for (const auto& n : reg.notices()) std::fprintf(stderr, "notice: %s\n", n.c_str());
  return reg;
}

}  // namespace brickyard::fw::cli
