#include "exec/file_search.hpp"
#include "loader/registry.hpp"

#include <brickyard/context.hpp>

#include <filesystem>

namespace brickyard::fw {

std::vector<std::string> data_dirs() {
  std::vector<std::string> dirs = env_path_list("BRICKYARD_DATA_PATH");
  const std::string prefix = install_prefix();
  if (!prefix.empty()) dirs.push_back((std::filesystem::path(prefix) / "share" / "brickyard" / "data").string());
  return dirs;
}

std::string find_data_file(const std::string& graph_file, std::string_view path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code ec;
  if (p.is_absolute()) {
    if (fs::is_regular_file(p, ec)) return p.string();
    // A FIFO or a device (/dev/zero) is there but cannot be a data file: a read would hang or never end.
    if (fs::exists(p, ec)) throw BadInput(p.string() + ": not a regular file");
    throw BadInput("file not found: " + p.string());
  }
  std::vector<fs::path> tried;
  if (!graph_file.empty()) tried.push_back(fs::path(graph_file).parent_path() / p);
  tried.push_back(fs::current_path(ec) / p);
  for (const auto& d : data_dirs()) tried.push_back(fs::path(d) / p);
  std::string where;
  for (const auto& t : tried) {
    if (fs::is_regular_file(t, ec)) return t.lexically_normal().string();
    where += "\n  " + t.lexically_normal().string();
  }
  throw BadInput("file '" + std::string(path) + "' not found; looked in:" + where);
}

}  // namespace brickyard::fw
