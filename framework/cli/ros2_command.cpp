// `brickyard ros2 msgs --out DIR`: the SDK's messages as a ROS 2 message package
// (cdr/ros2_msgs.hpp) in DIR: package.xml, CMakeLists.txt and msg/*.msg, for a colcon workspace.
// DIR is made, or holds this package already (written again, stale messages removed); any other
// folder is refused (exit 2), never written into.
// `brickyard ros2 idl --out FILE`: the same messages in IDL as ROS 2's DDS middlewares name them
// on the wire, for a DDS program without ROS 2 (written whole or not at all).
#include "cli/command_table.hpp"
#include "graph/diagnostics.hpp"
#include "record/recorder.hpp"

#include "cdr/ros2_msgs.hpp"
#include "io/whole_file.hpp"

#include <brickyard/msgs/registry.hpp>
#include <brickyard/version.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace brickyard::fw::cli {

namespace {

namespace fs = std::filesystem;

// Every type's definitions, each struct once, in the order the types' schemas define them.
cdr::IdlModel sdk_messages() {
  std::size_t count = 0;
  const msgs::TypeEntry* types = msgs::all_types(&count);
  cdr::IdlModel all;
  for (std::size_t i = 0; i < count; ++i) {
    const char* idl = idl_text(types[i].name);
    if (!idl) continue;
    const cdr::IdlModel one = cdr::parse_idl(omgidl_schema(idl));
    for (const std::string& q : one.defined) {
      if (all.structs.count(q)) continue;
      all.structs[q] = all.structs[cdr::idl_bare_name(q)] = one.structs.at(q);
      all.defined.push_back(q);
    }
  }
  return all;
}

// DIR may be written: missing, empty, or this package's (its package.xml names it).
void check_out_folder(const fs::path& dir, const std::string& package) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) throw InvalidInput("--out " + dir.string(), "not a folder");
  if (fs::is_empty(dir, ec)) return;
  std::ifstream xml(dir / "package.xml");
  std::stringstream text;
  text << xml.rdbuf();
  if (!xml || text.str().find("<name>" + package + "</name>") == std::string::npos)
    throw InvalidInput("--out " + dir.string(), "holds files and no " + package + " package: name a new or empty folder");
}

cdr::Ros2PackageInfo package_info() {
  cdr::Ros2PackageInfo info;
  info.version = BRICKYARD_SDK_VERSION;
  info.description = "Brickyard's messages (the SDK's IDL) for ROS 2 nodes: the same CDR as Brickyard's samples";
  return info;
}

int write_dds_idl(const Args& a) {
  if (!a.more.empty()) usage_error("ros2 idl", "takes no file, only --out FILE");
  if (a.out.empty()) usage_error("ros2 idl", "needs --out FILE (the IDL file to write)");
  std::error_code ec;
  if (fs::is_directory(a.out, ec)) throw InvalidInput("--out " + a.out, "a folder: name the IDL file to write");
  const cdr::Ros2PackageInfo info = package_info();
  io::write_whole_file(a.out, cdr::ros2_dds_idl(sdk_messages(), info));
  std::printf("ros2 idl: %s: module %s::msg::dds_, the types as ROS 2's DDS middlewares name them\n", a.out.c_str(), info.name.c_str());
  return 0;
}

}  // namespace

int cmd_ros2(const Args& a) {
  if (a.target == "idl") return write_dds_idl(a);
  if (a.target != "msgs")
    usage_error(a.target.empty() ? "ros2" : "ros2 " + a.target, "expected: brickyard ros2 msgs --out DIR, or brickyard ros2 idl --out FILE");
  if (!a.more.empty()) usage_error("ros2 msgs", "takes no file, only --out DIR");
  if (a.out.empty()) usage_error("ros2 msgs", "needs --out DIR (the package's folder, in a colcon workspace's src/)");
  const cdr::Ros2PackageInfo info = package_info();
  const std::vector<cdr::Ros2File> files = cdr::ros2_package(sdk_messages(), info);
  const fs::path dir(a.out);
  check_out_folder(dir, info.name);
  fs::create_directories(dir / "msg");
  std::set<std::string> written;
  for (const auto& f : files) {
    io::write_whole_file((dir / f.path).string(), f.text);
    written.insert(f.path);
  }
  for (const auto& e : fs::directory_iterator(dir / "msg"))  // a message the SDK no longer has
    if (!written.count("msg/" + e.path().filename().string())) fs::remove(e.path());
  std::printf("ros2 msgs: %s: package %s %s, %zu messages (build it in a colcon workspace: colcon build --packages-select %s)\n",
              a.out.c_str(), info.name.c_str(), info.version.c_str(), files.size() - 2, info.name.c_str());
  return 0;
}

}  // namespace brickyard::fw::cli
