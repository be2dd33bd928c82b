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

// Folders are added in search order, earliest first. A plugin name provided by a library of an
// earlier folder overrides the same name in a later folder (a notice says so): a user who
// installed a plugin can still run the build tree's copy with --plugin-path. Two libraries of
// one folder providing the same name are an error, as is one library declaring a name twice.
class Registry {
 public:
  // Loads every *.so in the folder, sorted by name. A missing folder is a problem of its own.
  void add_directory(const std::string& dir);
  // One library, searched after everything added before it (a folder of its own).
  void load_library(const std::string& path);

  const PluginEntry* find(const std::string& name) const;
  const std::vector<PluginEntry>& plugins() const { return plugins_; }
  const std::vector<LibraryProblem>& problems() const { return problems_; }
  const std::vector<std::string>& directories() const { return dirs_; }
  // "plugin 'acme.x' from <library> overrides the one in <library>", one per overridden plugin.
  const std::vector<std::string>& notices() const { return notices_; }

 private:
  // A plugin some library provides, overridden or not, and the folder it was found in (its
  // place in the search order).
  struct Provider {
    std::string name, library;
    std::size_t folder;
  };
  void load(const std::string& path, std::size_t folder);
  // The plugins of a library whose info checked out, each manifest checked: their problems, and
  // the plugins an earlier folder's override (notices), added to `problems` and `overridden`.
  std::vector<PluginEntry> read_plugins(const brickyard_library_info& info, const std::string& path, std::size_t folder,
                                        std::vector<std::string>& problems, std::vector<std::string>& overridden) const;

  std::vector<PluginEntry> plugins_;
  std::vector<LibraryProblem> problems_;
  std::vector<std::string> dirs_;
  std::vector<std::string> notices_;
  std::vector<Provider> providers_;
  std::size_t folders_ = 0;          // folders (and lone libraries) searched so far
  std::vector<std::string> loaded_;  // canonical paths already loaded
};

// Problems of a manifest on its own (names, ports, message types, params, triggers).
std::vector<std::string> check_manifest(const Manifest& m);

// Plugin folders in search order: explicit ones (--plugin-path, the graph's plugin_path), then
// $BRICKYARD_PLUGIN_PATH, then the folder beside the executable (build tree and install tree alike).
std::vector<std::string> default_plugin_dirs();
// The whole search order: the --plugin-path folders, the graph's plugin_path, then
// default_plugin_dirs().
std::vector<std::string> plugin_search_dirs(const std::vector<std::string>& command_line,
                                            const std::vector<std::string>& graph);
// The directories of a colon-separated environment variable (empty entries skipped).
std::vector<std::string> env_path_list(const char* var);
// <prefix> of this executable (<prefix>/bin/brickyard), or "" when unknown.
std::string install_prefix();

}  // namespace brickyard::fw
