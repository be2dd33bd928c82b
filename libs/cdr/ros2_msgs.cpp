#include "cdr/ros2_msgs.hpp"

#include <cctype>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

namespace brickyard::cdr {

namespace {

// The IDL primitives our messages use, and ROS 2's name for the one with the same CDR
// (rosidl's "Interface definition and language mapping": float64 is IDL double, byte is octet).
const std::map<std::string, std::string>& ros2_primitives() {
  static const std::map<std::string, std::string> names = {
      {"boolean", "bool"}, {"octet", "byte"},    {"int8", "int8"},       {"uint8", "uint8"},     {"int16", "int16"},
      {"short", "int16"},  {"uint16", "uint16"}, {"int32", "int32"},     {"long", "int32"},      {"uint32", "uint32"},
      {"int64", "int64"},  {"uint64", "uint64"}, {"float", "float32"},   {"double", "float64"}};
  return names;
}

// ROS 2's rules for names (rosidl_adapter): a type is CamelCase, a field lower_snake_case with no
// double or trailing underscore.
bool camel_case(const std::string& s) {
  if (s.empty() || !std::isupper(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) return false;
  return true;
}
bool snake_case(const std::string& s) {
  if (s.empty() || !std::islower(static_cast<unsigned char>(s[0])) || s.back() == '_' || s.find("__") != std::string::npos) return false;
  for (char c : s)
    if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

// "brickyard::msgs::Imu" -> "brickyard::msgs".
std::string module_of(const std::string& qualified) {
  const auto at = qualified.rfind("::");
  return at == std::string::npos ? std::string() : qualified.substr(0, at);
}

// The ROS 2 package a struct (by its bare name, as a member names it) belongs to.
using PackageOf = std::function<std::string(const std::string&)>;

std::string type_in(const IdlType& t, const PackageOf& package_of);
PackageOf one_package(const std::string& package);

// A type's .msg text. Ours say where they come from; ROS 2's standard types are theirs.
std::string msg_text(const std::string& name, const std::vector<IdlMember>& members, const PackageOf& package_of, bool ours = true) {
  std::string text = ours ? "# " + name + ": written by `brickyard ros2 msgs` from the SDK's IDL (sdk/msgs); do not edit.\n" : std::string();
  for (const IdlMember& m : members) {
    if (!snake_case(m.name)) throw std::invalid_argument("struct " + name + ": member '" + m.name + "' is not a ROS 2 field name (lower_snake_case)");
    try {
      text += type_in(m.type, package_of) + " " + m.name + "\n";
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("struct " + name + ", member '" + m.name + "': " + e.what());
    }
  }
  return text;
}

std::string package_xml(const Ros2PackageInfo& info) {
  return "<?xml version=\"1.0\"?>\n"
         "<?xml-model href=\"http://download.ros.org/schema/package_format3.xsd\" schematypens=\"http://www.w3.org/2001/XMLSchema\"?>\n"
         "<package format=\"3\">\n"
         "  <name>" + info.name + "</name>\n"
         "  <version>" + info.version + "</version>\n"
         "  <description>" + info.description + "</description>\n"
         "  <maintainer email=\"" + info.maintainer_email + "\">" + info.maintainer + "</maintainer>\n"
         "  <license>" + info.license + "</license>\n"
         "  <buildtool_depend>ament_cmake</buildtool_depend>\n"
         "  <buildtool_depend>rosidl_default_generators</buildtool_depend>\n"
         "  <exec_depend>rosidl_default_runtime</exec_depend>\n"
         "  <member_of_group>rosidl_interface_packages</member_of_group>\n"
         "  <export>\n"
         "    <build_type>ament_cmake</build_type>\n"
         "  </export>\n"
         "</package>\n";
}

std::string cmakelists(const Ros2PackageInfo& info, const std::vector<std::string>& msgs) {
  std::string text = "# Written by `brickyard ros2 msgs` from the SDK's IDL; do not edit.\n"
                     "cmake_minimum_required(VERSION 3.8)\n"
                     "project(" + info.name + ")\n"
                     "find_package(ament_cmake REQUIRED)\n"
                     "find_package(rosidl_default_generators REQUIRED)\n"
                     "rosidl_generate_interfaces(${PROJECT_NAME}\n";
  for (const auto& m : msgs) text += "  \"" + m + "\"\n";
  text += ")\n"
          "ament_export_dependencies(rosidl_default_runtime)\n"
          "ament_package()\n";
  return text;
}

// A member's type in IDL, a struct by its dds_ name.
std::string dds_idl_type(const IdlType& t) {
  switch (t.kind) {
    case IdlType::Primitive: return t.name;
    case IdlType::String: return t.bound ? "string<" + std::to_string(t.bound) + ">" : "string";
    case IdlType::Struct: return t.name + "_";
    case IdlType::Sequence: return "sequence<" + dds_idl_type(*t.of) + (t.bound ? ", " + std::to_string(t.bound) : "") + ">";
    case IdlType::Array: return dds_idl_type(*t.of);
  }
  return "?";
}

// The structs of `model` in order, each checked as ros2_package checks it: (qualified, bare) names.
std::vector<std::pair<std::string, std::string>> package_structs(const IdlModel& model) {
  std::vector<std::pair<std::string, std::string>> out;
  std::set<std::string> done;
  const std::string module = model.defined.empty() ? std::string() : module_of(model.defined.front());
  for (const std::string& qualified : model.defined) {
    if (!done.insert(qualified).second) continue;
    const std::string name = idl_bare_name(qualified);
    if (module_of(qualified) != module)
      throw std::invalid_argument("struct " + qualified + ": not in module " + module + " (one package, one module)");
    if (!camel_case(name)) throw std::invalid_argument("struct " + qualified + ": not a ROS 2 type name (CamelCase)");
    out.emplace_back(qualified, name);
  }
  return out;
}

// The structs a member's type names (through sequences and arrays), in order.
void struct_names(const IdlType& t, std::vector<std::string>& out) {
  if (t.kind == IdlType::Struct) out.push_back(t.name);
  else if (t.of) struct_names(*t.of, out);
}

}  // namespace

std::string ros2msg_schema(const IdlModel& model, const std::string& qualified, const std::string& package) {
  const auto top = model.structs.find(qualified);
  if (top == model.structs.end()) throw std::invalid_argument("no struct " + qualified);
  // A struct of a module "P::msg" is ROS 2's package P's (the standard types, cdr/ros2_std_types.hpp);
  // any other is `package`'s.
  std::map<std::string, std::string> packages;
  for (const std::string& q : model.defined) {
    const std::string module = module_of(q);
    const auto at = module.rfind("::msg");
    packages[idl_bare_name(q)] = at != std::string::npos && at + 5 == module.size() ? module.substr(0, at) : package;
  }
  const PackageOf package_of = [&packages, &package](const std::string& bare) {
    const auto it = packages.find(bare);
    return it == packages.end() ? package : it->second;
  };
  std::vector<std::string> order = {idl_bare_name(qualified)};
  std::set<std::string> seen(order.begin(), order.end());
  std::string out;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto it = model.structs.find(order[i]);
    if (it == model.structs.end()) throw std::invalid_argument("struct " + qualified + " uses " + order[i] + ", which is not defined");
    if (i > 0) out += "\n" + std::string(80, '=') + "\nMSG: " + package_of(order[i]) + "/" + order[i] + "\n";
    out += msg_text(order[i], *it->second, package_of, package_of(order[i]) == package);
    std::vector<std::string> used;
    for (const IdlMember& m : *it->second) struct_names(m.type, used);
    for (const std::string& u : used)
      if (seen.insert(idl_bare_name(u)).second) order.push_back(idl_bare_name(u));
  }
  return out;
}

std::string ros2_dds_idl(const IdlModel& model, const Ros2PackageInfo& info) {
  std::string text = "// " + info.name + " " + info.version + " as ROS 2's DDS middlewares name it on the wire: written by\n"
                     "// `brickyard ros2 idl` from the SDK's IDL (sdk/msgs); do not edit.\n"
                     "module " + info.name + " {\nmodule msg {\nmodule dds_ {\n";
  for (const auto& [qualified, name] : package_structs(model)) {
    msg_text(name, *model.structs.at(qualified), one_package(info.name));  // ROS 2's refusals, the same
    text += "@final struct " + name + "_ {\n";
    for (const IdlMember& m : *model.structs.at(qualified))
      text += "  " + dds_idl_type(m.type) + " " + m.name + (m.type.kind == IdlType::Array ? "[" + std::to_string(m.type.size) + "]" : "") + ";\n";
    text += "};\n";
  }
  return text + "};  // module dds_\n};  // module msg\n};  // module " + info.name + "\n";
}

namespace {

std::string type_in(const IdlType& t, const PackageOf& package_of) {
  switch (t.kind) {
    case IdlType::Primitive: {
      const auto it = ros2_primitives().find(t.name);
      if (it == ros2_primitives().end()) throw std::invalid_argument("type '" + t.name + "' has no ROS 2 twin");
      return it->second;
    }
    case IdlType::String: return t.bound ? "string<=" + std::to_string(t.bound) : "string";
    case IdlType::Struct: return package_of(t.name) + "/" + t.name;
    case IdlType::Sequence: {
      if (t.of->kind == IdlType::Sequence || t.of->kind == IdlType::Array)
        throw std::invalid_argument("a sequence of sequences or arrays has no ROS 2 form");
      return type_in(*t.of, package_of) + (t.bound ? "[<=" + std::to_string(t.bound) + "]" : "[]");
    }
    case IdlType::Array: {
      if (t.of->kind == IdlType::Sequence || t.of->kind == IdlType::Array)
        throw std::invalid_argument("an array of sequences or arrays has no ROS 2 form");
      return type_in(*t.of, package_of) + "[" + std::to_string(t.size) + "]";
    }
  }
  throw std::invalid_argument("unknown type");
}

// Every struct in `package`.
PackageOf one_package(const std::string& package) {
  return [package](const std::string&) { return package; };
}

}  // namespace

std::string ros2_type(const IdlType& t, const std::string& package) { return type_in(t, one_package(package)); }

std::vector<Ros2File> ros2_package(const IdlModel& model, const Ros2PackageInfo& info) {
  std::vector<Ros2File> files;
  std::vector<std::string> msgs;
  for (const auto& [qualified, name] : package_structs(model)) {
    msgs.push_back("msg/" + name + ".msg");
    files.push_back({msgs.back(), msg_text(name, *model.structs.at(qualified), one_package(info.name))});
  }
  files.push_back({"package.xml", package_xml(info)});
  files.push_back({"CMakeLists.txt", cmakelists(info, msgs)});
  return files;
}

}  // namespace brickyard::cdr
