#include "loader/registry.hpp"
#include "graph/names.hpp"
#include "exec/crash_guard.hpp"

#include <brickyard/msgs/registry.hpp>

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;

namespace brickyard::fw {
namespace {

bool is_elf(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  char magic[4] = {};
  f.read(magic, 4);
  return f.gcount() == 4 && std::memcmp(magic, "\x7f" "ELF", 4) == 0;
}

bool value_matches(ParamType t, const ParamValue& v) {
  switch (t) {
    case ParamType::boolean: return std::holds_alternative<bool>(v);
    case ParamType::integer: return std::holds_alternative<std::int64_t>(v);
    case ParamType::number: return std::holds_alternative<double>(v) || std::holds_alternative<std::int64_t>(v);
    case ParamType::string: return std::holds_alternative<std::string>(v);
    case ParamType::number_array: return std::holds_alternative<std::vector<double>>(v);
    case ParamType::json: return std::holds_alternative<JsonText>(v);
  }
  return false;
}

}  // namespace

namespace {

void check_ports(const Manifest& m, const std::string& who, std::vector<std::string>& p) {
  std::set<std::string> ports;
  for (const auto& port : m.ports) {
    if (!is_identifier(port.name)) p.push_back(who + ": port name '" + port.name + "' is not an identifier");
    if (!ports.insert(port.name).second) p.push_back(who + ": port '" + port.name + "' declared twice");
    // A port of any type (an AnyInput: "*"; an AnyOutput: "*" or "*PARAM", PARAM a string parameter).
    const bool any = is_any_message_type(port.type_name);
    if (any && port.direction == PortDirection::input && port.type_name != kAnyMessageType)
      p.push_back(who + ": input '" + port.name + "' of type " + port.type_name + ": an input of any type is \"*\"");
    if (any && port.type_name.size() > 1) {
      const ParamSpec* ps = m.param_spec(port.type_name.substr(1));
      if (!ps || ps->type != ParamType::string)
        p.push_back(who + ": output '" + port.name + "' takes its type from parameter '" + port.type_name.substr(1) + "', which is not a string parameter");
    }
    const auto* t = any ? nullptr : msgs::find_type(port.type_name.c_str());
    if (any) {
    } else if (!t) p.push_back(who + ": port '" + port.name + "' uses unknown message type " + port.type_name);
    else if (port.type_hash != t->hash)
      p.push_back(who + ": port '" + port.name + "' was built against another definition of " + port.type_name +
                  " (hash " + port.type_hash + ", host has " + t->hash + ")");
    if (port.direction == PortDirection::input && port.depth == 0)
      p.push_back(who + ": input '" + port.name + "' has depth 0");
  }
}

void check_params(const Manifest& m, const std::string& who, std::vector<std::string>& p) {
  std::set<std::string> params;
  for (const auto& ps : m.params) {
    if (!is_identifier(ps.name)) p.push_back(who + ": param name '" + ps.name + "' is not an identifier");
    if (!params.insert(ps.name).second) p.push_back(who + ": param '" + ps.name + "' declared twice");
    if (ps.default_value && !value_matches(ps.type, *ps.default_value))
      p.push_back(who + ": default of param '" + ps.name + "' is not a " + to_string(ps.type));
  }
}

void check_constraints(const Manifest& m, const std::string& who, std::vector<std::string>& p) {
  Params defaults;
  for (const auto& ps : m.params)
    if (ps.default_value && value_matches(ps.type, *ps.default_value)) defaults.set(ps.name, *ps.default_value);
  for (const auto& c : m.constraints) {
    bool numbers = true;
    for (const std::string* n : {&c.lower, &c.upper}) {
      const ParamSpec* ps = m.param_spec(*n);
      if (!ps || (ps->type != ParamType::number && ps->type != ParamType::integer)) {
        p.push_back(who + ": constraint names '" + *n + "', which is not a number param");
        numbers = false;
      }
    }
    if (!numbers) continue;
    if (auto e = c.violation(defaults); !e.empty()) p.push_back(who + ": its defaults break its own constraint: " + e);
  }
}

void check_triggers(const Manifest& m, const std::string& who, std::vector<std::string>& p) {
  for (const auto& t : m.triggers) {
    if (t.kind == TriggerSpec::Kind::periodic || t.kind == TriggerSpec::Kind::latency || t.kind == TriggerSpec::Kind::deadline) {
      const char* what = t.kind == TriggerSpec::Kind::periodic ? "periodic trigger" : t.kind == TriggerSpec::Kind::latency ? "latency" : "step deadline";
      const ParamSpec* ps = m.param_spec(t.ref);
      if (!ps || (ps->type != ParamType::number && ps->type != ParamType::integer))
        p.push_back(who + ": " + what + " names '" + t.ref + "', which is not a number param");
    } else {
      const PortSpec* ps = m.port(t.ref);
      if (!ps || ps->direction != PortDirection::input)
        p.push_back(who + ": on_input trigger names '" + t.ref + "', which is not an input port");
    }
  }
}

// A role the plugin claims must be one this host knows, and its ports must fit the role's.
void check_roles(const Manifest& m, const std::string& who, std::vector<std::string>& p) {
  for (const auto& r : m.roles) {
    const RoleContract* role = find_role(r);
    if (!role) {
      std::string known;
      for (const auto& c : role_contracts()) known += (known.empty() ? "" : ", ") + c.name;
      p.push_back(who + ": plays unknown role '" + r + "' (roles: " + known + ")");
      continue;
    }
    for (const auto& why : role_mismatches(m, *role)) p.push_back(who + ": plays role '" + r + "' but " + why);
  }
}

}  // namespace

std::vector<std::string> check_manifest(const Manifest& m) {
  std::vector<std::string> p;
  const std::string who = "plugin '" + m.name + "'";
  if (!is_dotted_name(m.name, 2, 64))
    p.push_back(who + ": name must look like area.name (lower case, digits, _)");
  if (m.version.empty()) p.push_back(who + ": empty version");
  check_ports(m, who, p);
  check_params(m, who, p);
  check_constraints(m, who, p);
  check_triggers(m, who, p);
  check_roles(m, who, p);
  return p;
}

void Registry::add_directory(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    problems_.push_back({dir, {"plugin folder does not exist or is not a folder"}});
    return;
  }
  dirs_.push_back(dir);
  const std::size_t folder = folders_++;
  std::vector<std::string> libs;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".so" && !e.is_directory()) libs.push_back(e.path().string());
  std::sort(libs.begin(), libs.end());
  for (const auto& l : libs) load(l, folder);
}

void Registry::load_library(const std::string& path) { load(path, folders_++); }

namespace {

// The library opened and its entry point called: its info, or null with the reason in `problems`.
const brickyard_library_info* open_library(const std::string& path, std::vector<std::string>& problems) {
  if (!is_elf(path)) {
    problems.push_back("not a shared object (no ELF header)");
    return nullptr;
  }
  // RTLD_NOW: an unresolved symbol is an error now, not a crash mid-race. RTLD_LOCAL: plugins'
  // symbols never interpose on each other.
  // The library's load-time code (static constructors, the entry point) runs here: a crash or an
  // exit() in it is named by the crash guard, not left a mute exit code.
  const crash_guard::Loading loading(path);
  void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char* e = dlerror();
    problems.push_back(std::string("dlopen failed: ") + (e ? e : "unknown error"));
    return nullptr;
  }
  // Never dlclose: see the header.
  auto entry = reinterpret_cast<brickyard_entry_point>(dlsym(h, BRICKYARD_ENTRY_POINT_NAME));
  if (!entry) {
    problems.push_back(std::string("missing entry point ") + BRICKYARD_ENTRY_POINT_NAME + " (export it with BRICKYARD_PLUGINS(...))");
    return nullptr;
  }
  const brickyard_library_info* info = entry();
  if (!info) problems.push_back(std::string(BRICKYARD_ENTRY_POINT_NAME) + " returned null");
  return info;
}

// The library's plugin ABI and C++ standard library against this host's, and its plugin table.
void check_library_info(const brickyard_library_info& info, std::vector<std::string>& problems) {
  const std::string theirs = std::to_string(info.abi_major) + "." + std::to_string(info.abi_minor);
  const std::string ours = std::to_string(BRICKYARD_ABI_MAJOR) + "." + std::to_string(BRICKYARD_ABI_MINOR);
  if (info.abi_major != BRICKYARD_ABI_MAJOR)
    problems.push_back("built against plugin ABI " + theirs + " (SDK " + (info.sdk_version ? info.sdk_version : "?") +
                       "), this host's is " + ours + ": rebuild the plugin against this SDK");
  else if (info.abi_minor > BRICKYARD_ABI_MINOR)
    problems.push_back("built against a newer SDK (ABI " + theirs + ") than this host (" + ours + ")");
  if (info.cxx_abi != BRICKYARD_CXX_ABI_TAG)
    problems.push_back("built with another C++ standard library ABI (tag " + std::to_string(info.cxx_abi) + ", host " +
                       std::to_string(BRICKYARD_CXX_ABI_TAG) + ")");
  if (info.plugin_count == 0) problems.push_back("declares no plugins");
  if (!info.plugins && info.plugin_count) problems.push_back("plugin table is null");
}

}  // namespace

void Registry::load(const std::string& path, std::size_t folder) {
  std::error_code ec;
  std::string canon = fs::weakly_canonical(path, ec).string();
  if (std::find(loaded_.begin(), loaded_.end(), canon) != loaded_.end()) return;
  loaded_.push_back(canon);

  LibraryProblem lp{path, {}};
  const brickyard_library_info* info = open_library(path, lp.problems);
  if (info) check_library_info(*info, lp.problems);
  if (!lp.problems.empty()) {
    problems_.push_back(lp);
    return;
  }
  std::vector<std::string> overridden;  // by a plugin of an earlier folder: notices, not entries
  std::vector<PluginEntry> found = read_plugins(*info, path, folder, lp.problems, overridden);
  if (!lp.problems.empty()) {
    problems_.push_back(lp);
    return;
  }
  for (auto& n : overridden) notices_.push_back(std::move(n));
  for (auto& e : found) {
    providers_.push_back({e.manifest.name, e.library, folder});
    if (!find(e.manifest.name)) plugins_.push_back(std::move(e));
  }
}

std::vector<PluginEntry> Registry::read_plugins(const brickyard_library_info& info, const std::string& path, std::size_t folder,
                                                std::vector<std::string>& problems, std::vector<std::string>& overridden) const {
  const auto* descs = static_cast<const PluginDescriptor*>(info.plugins);
  std::vector<PluginEntry> found;
  for (std::uint32_t i = 0; i < info.plugin_count; ++i) {
    PluginEntry e;
    try {
      e.manifest = descs[i].manifest();
    } catch (const std::exception& ex) {
      problems.push_back("manifest() of plugin #" + std::to_string(i) + " threw: " + ex.what());
      continue;
    }
    for (auto& m : check_manifest(e.manifest)) problems.push_back(m);
    auto same_folder = std::find_if(providers_.begin(), providers_.end(), [&](const Provider& p) {
      return p.folder == folder && p.name == e.manifest.name;
    });
    if (same_folder != providers_.end())
      problems.push_back("plugin '" + e.manifest.name + "' is also provided by " + same_folder->library);
    else if (const PluginEntry* earlier = find(e.manifest.name))
      overridden.push_back("plugin '" + e.manifest.name + "' from " + earlier->library + " overrides the one in " + path);
    for (const auto& f : found)
      if (f.manifest.name == e.manifest.name) problems.push_back("plugin '" + e.manifest.name + "' declared twice");
    e.descriptor = &descs[i];
    e.library = path;
    e.sdk_version = info.sdk_version ? info.sdk_version : "";
    found.push_back(std::move(e));
  }
  return found;
}

const PluginEntry* Registry::find(const std::string& name) const {
  for (const auto& p : plugins_)
    if (p.manifest.name == name) return &p;
  return nullptr;
}

std::vector<std::string> env_path_list(const char* var) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv(var)) {
    std::string s = env;
    for (std::size_t start = 0;;) {
      auto colon = s.find(':', start);
      std::string d = s.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
      if (!d.empty()) dirs.push_back(d);
      if (colon == std::string::npos) break;
      start = colon + 1;
    }
  }
  return dirs;
}

std::string install_prefix() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().parent_path().string();
}

std::vector<std::string> default_plugin_dirs() {
  std::vector<std::string> dirs = env_path_list("BRICKYARD_PLUGIN_PATH");
  const std::string prefix = install_prefix();
  std::error_code ec;
  if (!prefix.empty()) {
    fs::path d = fs::path(prefix) / "lib" / "brickyard" / "plugins";
    if (fs::is_directory(d, ec)) dirs.push_back(d.string());
  }
  return dirs;
}

std::vector<std::string> plugin_search_dirs(const std::vector<std::string>& command_line,
                                            const std::vector<std::string>& graph) {
  std::vector<std::string> dirs = command_line;
  dirs.insert(dirs.end(), graph.begin(), graph.end());
  for (auto& d : default_plugin_dirs()) dirs.push_back(std::move(d));
  return dirs;
}

}  // namespace brickyard::fw
