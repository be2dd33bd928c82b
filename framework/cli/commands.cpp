#include "cli/commands.hpp"
#include "graph/names.hpp"

#include "graph/diagnostics.hpp"

#include <brickyard/roles.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <sstream>
#include <vector>

namespace fs = std::filesystem;

namespace brickyard::fw {
namespace {

nlohmann::json value_json(const ParamValue& v) {
  return std::visit(
      [](const auto& x) -> nlohmann::json {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, JsonText>) return nlohmann::json::parse(x.text, nullptr, false);
        else return x;
      },
      v);
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t pos = 0; (pos = s.find(from, pos)) != std::string::npos; pos += to.size()) s.replace(pos, from.size(), to);
  return s;
}

}  // namespace

nlohmann::json manifest_to_json(const PluginEntry& p) {
  const Manifest& m = p.manifest;
  nlohmann::json j;
  j["name"] = m.name;
  j["version"] = m.version;
  j["description"] = m.description;
  j["library"] = p.library;
  j["sdk_version"] = p.sdk_version;
  j["roles"] = m.roles;
  j["ports"] = nlohmann::json::array();
  for (const auto& port : m.ports) {
    nlohmann::json pj{{"name", port.name},
                      {"direction", port.direction == PortDirection::input ? "input" : "output"},
                      {"type", port.type_name},
                      {"type_hash", port.type_hash},
                      {"description", port.description}};
    if (port.direction == PortDirection::input) {
      pj["required"] = port.required;
      pj["depth"] = port.depth;
    }
    j["ports"].push_back(pj);
  }
  j["params"] = nlohmann::json::array();
  for (const auto& ps : m.params) {
    nlohmann::json pj{{"name", ps.name}, {"type", to_string(ps.type)}, {"required", ps.required()},
                      {"unit", ps.unit}, {"description", ps.description}};
    pj["default"] = ps.default_value ? value_json(*ps.default_value) : nlohmann::json(nullptr);
    pj["min"] = ps.min ? nlohmann::json(*ps.min) : nlohmann::json(nullptr);
    pj["max"] = ps.max ? nlohmann::json(*ps.max) : nlohmann::json(nullptr);
    if (!ps.choices.empty()) pj["choices"] = ps.choices;
    j["params"].push_back(pj);
  }
  j["constraints"] = nlohmann::json::array();
  for (const auto& c : m.constraints)
    j["constraints"].push_back({{"lower", c.lower}, {"upper", c.upper}, {"strict", c.strict}});
  j["triggers"] = nlohmann::json::array();
  for (const auto& t : m.triggers) {
    if (t.kind == TriggerSpec::Kind::periodic) j["triggers"].push_back({{"kind", "periodic"}, {"rate_param", t.ref}});
    else if (t.kind == TriggerSpec::Kind::latency) j["triggers"].push_back({{"kind", "latency"}, {"seconds_param", t.ref}});
    else if (t.kind == TriggerSpec::Kind::deadline) j["triggers"].push_back({{"kind", "deadline"}, {"seconds_param", t.ref}});
    else j["triggers"].push_back({{"kind", "on_input"}, {"port", t.ref}});
  }
  return j;
}

std::string plugin_text(const PluginEntry& p) {
  std::ostringstream o;
  {
    const Manifest& m = p.manifest;
    o << m.name << " " << m.version << "  (" << p.library << ")\n";
    if (!m.description.empty()) o << "  " << m.description << "\n";
    for (const auto& r : m.roles) o << "  plays " << r << "\n";
    for (const auto& port : m.ports)
      o << "  " << (port.direction == PortDirection::input ? "in  " : "out ") << port.name << " : " << port.type_name
        << (port.direction == PortDirection::input && !port.required ? " (optional)" : "")
        << (port.description.empty() ? "" : "  — " + port.description) << "\n";
    for (const auto& ps : m.params) {
      o << "  param " << ps.name << " : " << to_string(ps.type);
      const double* d = ps.default_value ? std::get_if<double>(&*ps.default_value) : nullptr;
      if (d && std::isnan(*d)) o << " = NaN (off)";  // an optional value: off unless the graph sets it
      else if (ps.default_value) o << " = " << value_json(*ps.default_value).dump();
      else o << " (required)";
      if (!ps.unit.empty()) o << " [" << ps.unit << "]";
      if (ps.min || ps.max)
        o << " range " << (ps.min ? std::to_string(*ps.min) : "-inf") << ".." << (ps.max ? std::to_string(*ps.max) : "inf");
      if (!ps.description.empty()) o << "  — " << ps.description;
      o << "\n";
    }
    for (const auto& c : m.constraints)
      o << "  constraint " << c.lower << (c.strict ? " < " : " <= ") << c.upper << "\n";
    for (const auto& t : m.triggers)
      o << "  " << (t.kind == TriggerSpec::Kind::periodic ? "trigger periodic at param "
                    : t.kind == TriggerSpec::Kind::latency ? "outputs delivered after param "
                    : t.kind == TriggerSpec::Kind::deadline ? "step deadline at param "
                                                           : "trigger on input ")
        << t.ref << "\n";
    o << "\n";
  }
  return o.str();
}

std::string graph_dot(const GraphDecl& g, const Registry* reg) {
  auto q = [](const std::string& s) { return "\"" + replace_all(s, "\"", "\\\"") + "\""; };
  std::ostringstream o;
  o << "digraph " << q(g.name) << " {\n  rankdir=LR;\n  node [shape=box, style=rounded];\n";
  std::map<std::string, std::vector<std::string>> by_process;
  for (const auto& [name, n] : g.nodes) by_process[n.process].push_back(name);
  for (const auto& [proc, names] : by_process) {
    bool cluster = by_process.size() > 1;
    if (cluster) o << "  subgraph " << q("cluster_" + proc) << " {\n    label=" << q("process " + proc) << ";\n";
    for (const auto& name : names)
      o << (cluster ? "    " : "  ") << q(name) << " [label=" << q(name + "\\n" + g.nodes.at(name).plugin) << "];\n";
    if (cluster) o << "  }\n";
  }
  for (const auto& w : g.wires) {
    std::string type;
    if (reg)
      if (const auto* p = reg->find(g.nodes.at(w.from.node).plugin))
        if (const auto* port = p->manifest.port(w.from.port)) type = port->type_name.substr(port->type_name.rfind(':') + 1);
    o << "  " << q(w.from.node) << " -> " << q(w.to.node) << " [label="
      << q(w.from.port + " → " + w.to.port + (type.empty() ? "" : "\\n" + type)) << "];\n";
  }
  o << "}\n";
  return o.str();
}

std::string find_template_dir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  fs::path installed = exe.parent_path().parent_path() / "share" / "brickyard" / "template";
  if (fs::is_directory(installed, ec)) return installed.string();
#ifdef BRICKYARD_SOURCE_TEMPLATE_DIR
  if (fs::is_directory(BRICKYARD_SOURCE_TEMPLATE_DIR, ec)) return BRICKYARD_SOURCE_TEMPLATE_DIR;
#endif
  return {};
}

namespace {
std::string comma_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}
}  // namespace

std::string find_role_template_dir(const std::string& template_dir, const std::string& role) {
  const fs::path roles_dir = fs::path(template_dir).parent_path() / "role_templates";
  std::error_code ec;
  std::vector<std::string> with_template;
  for (const auto& r : role_contracts())
    if (!template_dir.empty() && fs::is_directory(roles_dir / r.name, ec)) with_template.push_back(r.name);
  const std::string have = "roles with one: " + (with_template.empty() ? std::string("none") : comma_list(with_template));
  if (!find_role(role)) {
    std::vector<std::string> all;
    for (const auto& r : role_contracts()) all.push_back(r.name);
    throw InvalidInput("--role " + role, "unknown role (roles: " + comma_list(all) + "; " + have + ")");
  }
  if (std::find(with_template.begin(), with_template.end(), role) == with_template.end())
    throw InvalidInput("--role " + role, "no template for this role yet (" + have + ")");
  return (roles_dir / role).string();
}

void scaffold_plugin(const std::string& name, const std::string& dir, const std::string& template_dir) {
  if (!is_dotted_name(name, 1, 2))
    throw InvalidInput("new-plugin " + quoted_name(name), "expected a name like my_filter or area.my_filter (lower case, digits, _)");
  if (template_dir.empty()) throw InvalidInput("new-plugin", "the SDK template folder was not found");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec))
    throw InvalidInput("--dir " + dir, "exists and is not empty; new-plugin never overwrites");
  const std::string full = name.find('.') == std::string::npos ? "user." + name : name;
  const std::string ident = replace_all(full.substr(full.find('.') + 1), ".", "_");
  std::string cls;
  bool up = true;
  for (char c : ident) {
    if (c == '_') { up = true; continue; }
    cls += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  fs::create_directories(dir);
  for (const auto& e : fs::recursive_directory_iterator(template_dir)) {
    fs::path rel = fs::relative(e.path(), template_dir);
    fs::path dst = fs::path(dir) / rel;
    if (e.is_directory()) {
      fs::create_directories(dst);
      continue;
    }
    std::ifstream in(e.path(), std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    // The template is a working project named example.my_plugin: rename it.
    std::string text =
        replace_all(replace_all(replace_all(ss.str(), "example.my_plugin", full), "MyPlugin", cls), "my_plugin", ident);
    std::ofstream(dst, std::ios::binary) << text;
  }
}

}  // namespace brickyard::fw
