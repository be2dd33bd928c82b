#pragma once
#include "graph/resolve.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace brickyard::fw {

nlohmann::json manifest_to_json(const PluginEntry& p);
// One plugin's manifest as text: what `brickyard plugins` prints for it.
std::string plugin_text(const PluginEntry& p);
std::string graph_dot(const GraphDecl& g, const Registry* reg);
// Copies the SDK template to dir/, naming the plugin. Throws InvalidInput on bad NAME or DIR.
void scaffold_plugin(const std::string& name, const std::string& dir, const std::string& template_dir);
std::string find_template_dir();
// The project of a role's template beside the SDK template (role_templates/ROLE). Throws
// InvalidInput naming the role: unknown, or known but without a template (listing those with one).
std::string find_role_template_dir(const std::string& template_dir, const std::string& role);

}  // namespace brickyard::fw
