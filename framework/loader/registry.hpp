#pragma once
// Finds plugin libraries, checks their ABI and manifests, and keeps them loaded for the life
// of the process (dlclose while plugin objects or DDS entities live crashes; we never do it).
#include <brickyard/plugin.hpp>

#include <string>
#include <vector>

namespace brickyard::fw {

struct PluginEntry {
  Manifest manifest;
  const PluginDescriptor* descriptor = nullptr;
  std::string library;  // path of the shared object
  std::string sdk_version;
};

struct LibraryProblem {
  std::string library;
  std::vector<std::string> problems;  // every problem of the library, reported together
};

class Registry {
 public:
  // Loads every *.so in the folder, sorted by name. A missing folder is a problem of its own.
  void add_directory(const std::string& dir);
  void load_library(const std::string& path);

  const PluginEntry* find(const std::string& name) const;
  const std::vector<PluginEntry>& plugins() const { return plugins_; }
  const std::vector<LibraryProblem>& problems() const { return problems_; }
  const std::vector<std::string>& directories() const { return dirs_; }

 private:
  std::vector<PluginEntry> plugins_;
  std::vector<LibraryProblem> problems_;
  std::vector<std::string> dirs_;
  std::vector<std::string> loaded_;  // canonical paths already loaded
};

// Problems of a manifest on its own (names, ports, message types, params, triggers).
std::vector<std::string> check_manifest(const Manifest& m);

// Plugin folders in search order: explicit ones (--plugin-path, the graph's plugin_path), then
// $BRICKYARD_PLUGIN_PATH, then the folder beside the executable (build tree and install tree alike).
std::vector<std::string> default_plugin_dirs();
// The directories of a colon-separated environment variable (empty entries skipped).
std::vector<std::string> env_path_list(const char* var);
// <prefix> of this executable (<prefix>/bin/brickyard), or "" when unknown.
std::string install_prefix();

}  // namespace brickyard::fw
