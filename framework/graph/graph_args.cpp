#include "graph/graph_args.hpp"

#include "graph/graph.hpp"
#include "graph/json_scan.hpp"
#include "graph/names.hpp"

#include <cctype>
#include <map>

namespace brickyard::fw {
namespace {

using nlohmann::json;

bool identifier(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  return true;
}

struct Filler {
  const std::map<std::string, json>& values;
  const std::string& file;
  Diagnostics& d;

  // The string with every ${name} replaced; `whole` set when it is exactly one ${name}.
  json fill(const std::string& s, const std::string& ptr) {
    if (s.size() > 3 && s.rfind("${", 0) == 0 && s.back() == '}' && s.find('}') == s.size() - 1) {
      const std::string name = s.substr(2, s.size() - 3);
      if (auto it = values.find(name); it != values.end()) return it->second;
    }
    std::string out;
    for (std::size_t at = 0; at < s.size();) {
      const std::size_t open = s.find("${", at);
      if (open == std::string::npos) {
        out += s.substr(at);
        break;
      }
      const std::size_t close = s.find('}', open);
      if (close == std::string::npos) {
        out += s.substr(at);
        break;
      }
      out += s.substr(at, open - at);
      const std::string name = s.substr(open + 2, close - open - 2);
      auto it = values.find(name);
      if (it == values.end()) {
        d.add(at_ptr(ptr), "argument \"" + name + "\" is used but the graph's \"args\" does not declare it");
      } else if (it->second.is_string()) {
        out += it->second.get<std::string>();
      } else if (it->second.is_number() || it->second.is_boolean()) {
        out += it->second.dump();
      } else {
        d.add(at_ptr(ptr), "argument \"" + name + "\" is " + std::string(it->second.type_name()) +
                               ": only a string, a number or a boolean can stand inside text");
      }
      at = close + 1;
    }
    return out;
  }

  std::string at_ptr(const std::string& ptr) const { return at(file, ptr); }

  void walk(json& j, const std::string& ptr, int depth) {
    if (depth > 64) return;  // the depth check has already refused such a file
    if (j.is_string()) {
      const std::string& s = j.get_ref<const std::string&>();
      if (s.find("${") != std::string::npos) j = fill(s, ptr);
    } else if (j.is_object()) {
      for (auto it = j.begin(); it != j.end(); ++it) walk(it.value(), ptr + "/" + pointer_escape(it.key()), depth + 1);
    } else if (j.is_array()) {
      for (std::size_t i = 0; i < j.size(); ++i) walk(j[i], ptr + "/" + std::to_string(i), depth + 1);
    }
  }
};

}  // namespace

void apply_args(json& root, const std::vector<std::string>& args, const std::string& file, Diagnostics& d) {
  std::map<std::string, json> values;
  if (root.contains("args")) {
    if (!root["args"].is_object()) {
      d.add(at(file, "/args"), std::string("expected an object of argument names and default values, found ") + root["args"].type_name());
    } else {
      for (auto it = root["args"].begin(); it != root["args"].end(); ++it) {
        if (!identifier(it.key())) d.add(at(file, "/args/" + pointer_escape(it.key())), "argument name \"" + it.key() + "\" must be letters, digits and _");
        else values[it.key()] = it.value();
      }
    }
    root.erase("args");
  }
  for (const auto& a : args) {
    const std::size_t eq = a.find('=');
    const std::string name = eq == std::string::npos ? a : a.substr(0, eq);
    if (eq == std::string::npos || !identifier(name)) {
      d.add("--arg " + a, "expected name=value");
      continue;
    }
    if (!values.count(name)) {
      std::string list;
      for (const auto& [n, v] : values) list += (list.empty() ? "" : ", ") + n;
      d.add("--arg " + a, "the graph declares no argument \"" + name + "\" (declared: " + (list.empty() ? "none" : list) + ")");
      continue;
    }
    if (auto deep = find_excess_depth(a.substr(eq + 1), kMaxValueDepth)) {
      d.add("--arg " + quoted_name(a), "the value: " + deep->message);
      continue;
    }
    // As --set: a value that parses as JSON is taken as such, anything else is a string.
    json v = json::parse(a.substr(eq + 1), nullptr, false);
    if (v.is_discarded()) v = a.substr(eq + 1);
    values[name] = v;
  }
  Filler f{values, file, d};
  f.walk(root, "", 0);
}

}  // namespace brickyard::fw
