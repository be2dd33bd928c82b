#include "graph/graph.hpp"
#include "graph/names.hpp"

#include "graph/diagnostics.hpp"
#include "graph/graph_args.hpp"
#include "graph/json_scan.hpp"

#include <brickyard/roles.hpp>

#include "io/bounded_read.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace brickyard::fw {
namespace {

using nlohmann::json;
constexpr int kMaxDepth = 64;
// A graph file, included or not: a 100,000-node graph is about 11 MB; a file larger than this is
// no graph a person wrote (and /dev/zero-like sources never end).
constexpr std::size_t kMaxGraphFileBytes = 64u << 20;

// The text of a graph file, or why it cannot be had: missing, not a regular file (a FIFO would
// block the open, a device never end), larger than kMaxGraphFileBytes, unreadable.
bool read_graph_text(const std::filesystem::path& path, std::string& text, std::string& why) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return why = "does not exist", false;
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path.string(), kMaxGraphFileBytes, bytes, error)) {
    const std::string named = path.string() + ": ";  // the reason, without the path the caller names itself
    why = error.rfind(named, 0) == 0 ? error.substr(named.size()) : error;
    return false;
  }
  text.assign(bytes.begin(), bytes.end());
  return true;
}

const char* type_word(const json& j) {
  switch (j.type()) {
    case json::value_t::object: return "object";
    case json::value_t::array: return "array";
    case json::value_t::string: return "string";
    case json::value_t::boolean: return "boolean";
    case json::value_t::null: return "null";
    case json::value_t::number_float: return "number";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "integer";
    default: return "value";
  }
}

struct Ctx {
  const std::string& file;
  Diagnostics& d;
  const GraphDecl* g = nullptr;  // when set, a pointer is named in the file that declared its value
  void err(const std::string& ptr, const std::string& msg) { d.add(g ? g->where(ptr) : at(file, ptr), msg); }
  bool expect(const json& j, json::value_t t, const char* word, const std::string& ptr) {
    bool ok = j.type() == t || (t == json::value_t::number_float && j.is_number()) ||
              (t == json::value_t::number_integer && j.is_number_integer());
    if (!ok) err(ptr, std::string("expected ") + word + ", found " + type_word(j));
    return ok;
  }
  void only_keys(const json& obj, const std::set<std::string>& allowed, const std::string& ptr) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      if (allowed.count(it.key())) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      err(ptr + "/" + pointer_escape(it.key()), "unknown key \"" + it.key() + "\" (allowed: " + list + ")");
    }
  }
};

std::optional<Endpoint> parse_endpoint(const json& j, const std::string& ptr, Ctx& c) {
  if (!c.expect(j, json::value_t::string, "string \"node.port\"", ptr)) return std::nullopt;
  const std::string s = j.get<std::string>();
  auto dot = s.find('.');
  if (dot == std::string::npos || s.find('.', dot + 1) != std::string::npos ||
      !is_identifier(std::string_view(s).substr(0, dot)) || !is_identifier(std::string_view(s).substr(dot + 1))) {
    c.err(ptr, "expected \"node.port\", found \"" + quoted_name(s) + "\"");
    return std::nullopt;
  }
  return Endpoint{s.substr(0, dot), s.substr(dot + 1)};
}

void parse_clock(const json& j, GraphDecl& g, Ctx& c) {
  if (!c.expect(j, json::value_t::object, "object", "/clock")) return;
  c.only_keys(j, {"mode", "step_s", "duration_s"}, "/clock");
  if (j.contains("mode") && c.expect(j["mode"], json::value_t::string, "string", "/clock/mode")) {
    auto m = j["mode"].get<std::string>();
    if (m == "sim") g.clock.sim = true;
    else if (m == "real") g.clock.sim = false;
    else c.err("/clock/mode", "expected \"sim\" or \"real\", found \"" + m + "\"");
  }
  if (j.contains("step_s") && c.expect(j["step_s"], json::value_t::number_float, "number", "/clock/step_s")) {
    double v = j["step_s"].get<double>();
    if (!(v >= 1e-6 && v <= 1.0)) c.err("/clock/step_s", "expected a step from 1e-06 to 1 s, found " + j["step_s"].dump());
    else g.clock.step_s = v;
  }
  if (j.contains("duration_s") &&
      c.expect(j["duration_s"], json::value_t::number_float, "number", "/clock/duration_s")) {
    double v = j["duration_s"].get<double>();
    if (!(v > 0 && v <= kMaxDuration_s))
      c.err("/clock/duration_s", "expected a positive duration of at most 1e7 s, found " + j["duration_s"].dump());
    else g.clock.duration_s = v;
  }
}

void parse_string_list(const json& j, std::vector<std::string>& out, const std::string& ptr, Ctx& c) {
  if (!c.expect(j, json::value_t::array, "array of strings", ptr)) return;
  out.clear();
  for (std::size_t i = 0; i < j.size(); ++i)
    if (c.expect(j[i], json::value_t::string, "string", ptr + "/" + std::to_string(i))) out.push_back(j[i]);
}

// transport.KEY, one of two words: `second` true when it is the second.
void transport_choice(const json& j, const char* key, const char* first, const char* second, Ctx& c, bool& is_second) {
  const std::string at = std::string("/transport/") + key;
  if (!j.contains(key) || !c.expect(j[key], json::value_t::string, "string", at)) return;
  const std::string v = j[key];
  if (v == first || v == second) is_second = v == second;
  else c.err(at, std::string("expected \"") + first + "\" or \"" + second + "\", found \"" + v + "\"");
}

// transport.KEY, seconds in (0, 600].
void transport_seconds(const json& j, const char* key, Ctx& c, double& out) {
  const std::string at = std::string("/transport/") + key;
  if (!j.contains(key) || !c.expect(j[key], json::value_t::number_float, "number", at)) return;
  const double t = j[key].get<double>();
  if (!(t > 0 && t <= 600)) c.err(at, "expected seconds, more than 0 and at most 600, found " + j[key].dump());
  else out = t;
}

void parse_transport(const json& j, GraphDecl& g, Ctx& c) {
  if (!c.expect(j, json::value_t::object, "object", "/transport")) return;
  c.only_keys(j, {"domain", "interfaces", "peers", "startup_timeout_s", "end_timeout_s", "naming", "foreign_writers", "shared_memory", "security"}, "/transport");
  if (j.contains("security") && c.expect(j["security"], json::value_t::string, "string", "/transport/security")) {
    g.transport.security = j["security"];  // "": by default (a graph argument's default, say)
  }
  if (j.contains("shared_memory") && c.expect(j["shared_memory"], json::value_t::boolean, "boolean", "/transport/shared_memory"))
    g.transport.shared_memory = j["shared_memory"];
  transport_choice(j, "foreign_writers", "ignore", "accept", c, g.transport.accept_foreign_writers);
  transport_choice(j, "naming", "brickyard", "ros2", c, g.transport.ros2_naming);
  transport_seconds(j, "startup_timeout_s", c, g.transport.startup_timeout_s);
  transport_seconds(j, "end_timeout_s", c, g.transport.end_timeout_s);
  if (j.contains("domain") && c.expect(j["domain"], json::value_t::number_integer, "integer", "/transport/domain")) {
    if (!j["domain"].is_number_integer()) c.err("/transport/domain", "expected integer, found " + j["domain"].dump());
    else if (j["domain"].get<long long>() < 0 || j["domain"].get<long long>() > 232)
      c.err("/transport/domain", "expected a DDS domain id from 0 to 232, found " + j["domain"].dump());
    else g.transport.domain = j["domain"].get<int>();
  }
  if (j.contains("interfaces")) parse_string_list(j["interfaces"], g.transport.interfaces, "/transport/interfaces", c);
  if (j.contains("peers")) parse_string_list(j["peers"], g.transport.peers, "/transport/peers", c);
}

void parse_live(const json& j, GraphDecl& g, Ctx& c) {
  if (!c.expect(j, json::value_t::object, "object", "/live")) return;
  c.only_keys(j, {"port", "address", "cloud_hz"}, "/live");
  if (j.contains("cloud_hz")) {
    const json& v = j["cloud_hz"];
    if (!v.is_number() || !(v.get<double>() >= 0) || v.get<double>() > 1000)
      c.err("/live/cloud_hz", "expected clouds a second from 0 (every one) to 1000, found " + v.dump().substr(0, 40));
    else g.live.cloud_hz = v.get<double>();
  }
  if (j.contains("port") && c.expect(j["port"], json::value_t::number_integer, "integer", "/live/port")) {
    if (!j["port"].is_number_integer() || j["port"].get<long long>() < 0 || j["port"].get<long long>() > 65535)
      c.err("/live/port", "expected a port from 0 to 65535, found " + j["port"].dump());
    else g.live.port = j["port"].get<int>();
  }
  if (j.contains("address") && c.expect(j["address"], json::value_t::string, "string", "/live/address")) g.live.address = j["address"].get<std::string>();
}

// "processes": {"NAME": {"restart": "never" | "on-failure", "max_restarts", "backoff_s", "may_die"}};
// every NAME must be a process some node runs in (checked after the nodes).
void parse_processes(const json& j, GraphDecl& g, Ctx& c) {
  if (!c.expect(j, json::value_t::object, "object", "/processes")) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string ptr = "/processes/" + pointer_escape(it.key());
    const json& p = it.value();
    if (!c.expect(p, json::value_t::object, "object", ptr)) continue;
    c.only_keys(p, {"restart", "max_restarts", "backoff_s", "may_die", "description"}, ptr);
    ProcessDecl pd;
    if (p.contains("restart") && c.expect(p["restart"], json::value_t::string, "string", ptr + "/restart")) {
      const std::string r = p["restart"];
      if (r == "never") pd.restart = ProcessDecl::Restart::never;
      else if (r == "on-failure") pd.restart = ProcessDecl::Restart::on_failure;
      else c.err(ptr + "/restart", "expected \"never\" or \"on-failure\", found \"" + r + "\"");
    }
    if (p.contains("max_restarts") && c.expect(p["max_restarts"], json::value_t::number_integer, "integer", ptr + "/max_restarts")) {
      if (!p["max_restarts"].is_number_integer() || p["max_restarts"].get<long long>() < 0 || p["max_restarts"].get<long long>() > 1000)
        c.err(ptr + "/max_restarts", "expected an integer from 0 to 1000, found " + p["max_restarts"].dump());
      else pd.max_restarts = p["max_restarts"].get<int>();
    }
    if (p.contains("backoff_s") && c.expect(p["backoff_s"], json::value_t::number_float, "number", ptr + "/backoff_s")) {
      const double b = p["backoff_s"].get<double>();
      if (!(b >= 0 && b <= 60)) c.err(ptr + "/backoff_s", "expected seconds from 0 to 60, found " + p["backoff_s"].dump());
      else pd.backoff_s = b;
    }
    if (p.contains("may_die") && c.expect(p["may_die"], json::value_t::boolean, "boolean", ptr + "/may_die")) pd.may_die = p["may_die"];
    if (p.contains("description")) c.expect(p["description"], json::value_t::string, "string", ptr + "/description");
    bool used = false;
    for (const auto& [_, n] : g.nodes) used = used || n.process == it.key();
    if (!used) c.err(ptr, "no node runs in process \"" + it.key() + "\"");
    g.processes[it.key()] = pd;
  }
}

// What --set changed of a node: each parameter's origin, and a plugin it swapped.
struct SetOrigins {
  std::map<std::string, std::map<std::string, std::string>> params;  // node -> param -> "--set ..."
  std::map<std::string, std::string> plugin;                         // node -> "--set NODE.plugin=..."
  std::map<std::string, std::string> replaced;                       // node -> the file's plugin
};

void apply_sets(json& root, const std::vector<std::string>& sets, Diagnostics& d, SetOrigins& origin) {
  for (const auto& s : sets) {
    // NODE.PARAM=VALUE, the two names identifiers (checked in one pass: no regex on input).
    const std::size_t eq = s.find('='), dot = s.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq || !is_identifier(std::string_view(s).substr(0, dot)) ||
        !is_identifier(std::string_view(s).substr(dot + 1, eq - dot - 1))) {
      d.add("--set " + quoted_name(s), "expected node.param=value");
      continue;
    }
    const std::string node = s.substr(0, dot), param = s.substr(dot + 1, eq - dot - 1), text = s.substr(eq + 1);
    if (!root.is_object() || !root.contains("nodes") || !root["nodes"].is_object() || !root["nodes"].contains(node)) {
      d.add("--set " + quoted_name(s), "the graph has no node \"" + node + "\"");
      continue;
    }
    json& n = root["nodes"][node];
    if (!n.is_object()) continue;  // reported by the structural check
    // NODE.plugin=NAME swaps the node's plugin (a planner by name), checked like the file's; the
    // node's params stay and must suit the new plugin, which must play the replaced one's roles.
    if (param == "plugin") {
      if (n.contains("plugin") && n["plugin"].is_string() && !origin.replaced.count(node))
        origin.replaced[node] = n["plugin"].get<std::string>();
      n["plugin"] = text;
      origin.plugin[node] = "--set " + quoted_name(s);
      continue;
    }
    if (!n.contains("params")) n["params"] = json::object();
    if (!n["params"].is_object()) continue;
    if (auto deep = find_excess_depth(text, kMaxValueDepth)) {
      d.add("--set " + quoted_name(s), "the value: " + deep->message);
      continue;
    }
    // A value that parses as JSON is taken as such (numbers, true, [1,2]); anything else is a string.
    json v = json::parse(text, nullptr, false);
    if (v.is_discarded()) v = text;
    n["params"][param] = v;
    origin.params[node][param] = "--set " + s;
  }
}


// One node of /nodes, or none when it is not an object (reported).
std::optional<NodeDecl> parse_node(const std::string& name, const json& n, SetOrigins& origin, Ctx& c) {
  const std::string ptr = "/nodes/" + pointer_escape(name);
  if (!c.expect(n, json::value_t::object, "object", ptr)) return std::nullopt;
  c.only_keys(n, {"plugin", "role", "params", "process", "deadline_s", "description"}, ptr);
  NodeDecl nd;
  nd.name = name;
  if (!n.contains("plugin")) c.err(ptr, "missing key \"plugin\"");
  else if (c.expect(n["plugin"], json::value_t::string, "string", ptr + "/plugin")) nd.plugin = n["plugin"];
  if (n.contains("role") && c.expect(n["role"], json::value_t::string, "string", ptr + "/role")) {
    nd.role = n["role"];
    if (!find_role(nd.role)) {
      std::string known;
      for (const auto& r : role_contracts()) known += (known.empty() ? "" : ", ") + r.name;
      c.err(ptr + "/role", "unknown role \"" + quoted_name(nd.role) + "\" (roles: " + known + ")");
    }
  }
  if (n.contains("params") && c.expect(n["params"], json::value_t::object, "object", ptr + "/params"))
    nd.params = n["params"];
  if (n.contains("process") && c.expect(n["process"], json::value_t::string, "string", ptr + "/process")) {
    nd.process = n["process"];
    if (!is_identifier(nd.process))
      c.err(ptr + "/process", "process name \"" + quoted_name(nd.process) + "\" must be an identifier of at most " + std::to_string(kMaxNameLength) + " characters");
  }
  if (n.contains("deadline_s") && c.expect(n["deadline_s"], json::value_t::number_float, "number", ptr + "/deadline_s")) {
    if (!(n["deadline_s"].get<double>() > 0 && n["deadline_s"].get<double>() <= 3600))
      c.err(ptr + "/deadline_s", "expected seconds, more than 0 and at most 3600, found " + n["deadline_s"].dump());
    else nd.deadline_s = n["deadline_s"].get<double>();
  }
  if (nd.process.empty()) nd.process = kDefaultProcess;
  nd.param_origin = origin.params[nd.name];
  if (origin.plugin.count(nd.name)) {
    nd.plugin_origin = origin.plugin[nd.name];
    nd.replaced_plugin = origin.replaced[nd.name];
  }
  return nd;
}

}  // namespace

std::string pointer_escape(const std::string& token) {
  std::string out;
  for (char ch : token) {
    if (ch == '~') out += "~0";
    else if (ch == '/') out += "~1";
    else out += ch;
  }
  return out;
}

std::string at(const std::string& file, const std::string& pointer) { return file + "#" + pointer; }

namespace {

// The text of one graph file as JSON, with the checks a DOM parser cannot make; errors at the
// file's line and column.
json parse_checked(const std::string& text, const std::string& file, Diagnostics& d) {
  auto located = [&](std::size_t off, const std::string& msg) {
    auto p = position_of(text, off);
    d.add(file + ":" + std::to_string(p.line) + ":" + std::to_string(p.column), msg);
    d.raise_if_any();
  };
  if (auto f = find_excess_depth(text, kMaxDepth)) located(f->offset, f->message);
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string msg = e.what();
    // nlohmann's text starts with "[json.exception.parse_error.101] parse error at line 1, column 2: "
    auto colon = msg.find(": ", msg.find("parse error"));
    located(e.byte > 0 ? e.byte - 1 : 0, "invalid JSON: " + (colon == std::string::npos ? msg : msg.substr(colon + 2)));
  } catch (const json::out_of_range& e) {  // a number no double holds: the parser does not say where
    if (auto f = find_number_overflow(text)) located(f->offset, f->message);
    located(0, std::string("invalid JSON: ") + e.what());
  }
  if (auto f = find_duplicate_key(text)) located(f->offset, f->message);
  return root;
}

// Graphs that include graphs: "include": ["base.json", ...], each relative to the
// including file, read first and in order; the including file then overrides what they declare,
// object by object (a node's params one by one), and appends its wires to theirs. Every value
// keeps the file and pointer that declared it (GraphDecl::where). A cycle is refused, named.
using Provenance = std::map<std::string, std::pair<std::string, std::string>>;  // pointer -> file, pointer there

// Where `src` says pointer q came from: its longest declared prefix, and the rest of q below it.
std::pair<std::string, std::string> origin_of(const Provenance& src, const std::string& q) {
  for (std::string p = q;;) {
    if (auto it = src.find(p); it != src.end()) return {it->second.first, it->second.second + q.substr(p.size())};
    if (p.empty()) return {"", q};
    p = p.substr(0, p.rfind('/'));
  }
}

// dst's pointer p now holds what src had at q: its origin, and those of everything below it.
void copy_provenance(Provenance& dst, const std::string& p, const Provenance& src, const std::string& q) {
  for (auto it = dst.lower_bound(p); it != dst.end() && it->first.compare(0, p.size(), p) == 0;)
    it = (it->first.size() == p.size() || it->first[p.size()] == '/') ? dst.erase(it) : std::next(it);
  dst[p] = origin_of(src, q);
  for (auto it = src.lower_bound(q + "/"); it != src.end() && it->first.compare(0, q.size() + 1, q + "/") == 0; ++it)
    dst[p + it->first.substr(q.size())] = it->second;
}

void fold(json& into, Provenance& into_prov, const json& over, const Provenance& over_prov, const std::string& ptr = "",
          const std::string& over_ptr = "") {
  for (auto it = over.begin(); it != over.end(); ++it) {
    const std::string p = ptr + "/" + pointer_escape(it.key()), q = over_ptr + "/" + pointer_escape(it.key());
    if (ptr.empty() && it.key() == "include") continue;
    if (ptr.empty() && it.key() == "wires" && it->is_array() && into.contains("wires") && into["wires"].is_array()) {
      for (std::size_t k = 0; k < it->size(); ++k) {
        copy_provenance(into_prov, "/wires/" + std::to_string(into["wires"].size()), over_prov, q + "/" + std::to_string(k));
        into["wires"].push_back((*it)[k]);
      }
      continue;
    }
    if (it->is_object() && into.contains(it.key()) && into[it.key()].is_object()) {
      fold(into[it.key()], into_prov, *it, over_prov, p, q);
      continue;
    }
    into[it.key()] = *it;
    copy_provenance(into_prov, p, over_prov, q);
  }
}

json compose(const std::string& text, const std::string& file, std::vector<std::string>& chain, Provenance& prov, Diagnostics& d) {
  json root = parse_checked(text, file, d);
  Provenance own = {{"", {file, ""}}};
  if (!root.is_object() || !root.contains("include")) {
    prov = own;
    return root;
  }
  Ctx c{file, d};
  const json& inc = root["include"];
  std::vector<std::string> files;
  if (inc.is_string()) files.push_back(inc.get<std::string>());
  else if (c.expect(inc, json::value_t::array, "array of file names", "/include"))
    for (std::size_t k = 0; k < inc.size(); ++k)
      if (c.expect(inc[k], json::value_t::string, "string", "/include/" + std::to_string(k))) files.push_back(inc[k].get<std::string>());
  d.raise_if_any();
  json merged = json::object();
  prov.clear();
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  for (std::size_t k = 0; k < files.size(); ++k) {
    const std::string where = at(file, "/include" + (inc.is_string() ? std::string() : "/" + std::to_string(k)));
    const std::filesystem::path path = std::filesystem::path(files[k]).is_relative() ? dir / files[k] : std::filesystem::path(files[k]);
    std::error_code ec;
    const std::string canon = std::filesystem::weakly_canonical(path, ec).string();
    if (std::find(chain.begin(), chain.end(), canon) != chain.end()) {
      std::string loop;
      for (const auto& f : chain) loop += f + " includes ";
      d.add(where, "an include cycle: " + loop + canon);
      d.raise_if_any();
    }
    if (chain.size() >= 16) {
      d.add(where, "includes nest deeper than 16 files");
      d.raise_if_any();
    }
    std::string text, why;
    if (!read_graph_text(path, text, why)) {
      d.add(where, "included file " + path.string() + ": " + why);
      d.raise_if_any();
    }
    chain.push_back(canon);
    Provenance part_prov;
    json part = compose(text, path.string(), chain, part_prov, d);
    chain.pop_back();
    if (!part.is_object()) {
      d.add(path.string() + "#", std::string("expected object, found ") + type_word(part));
      d.raise_if_any();
    }
    // A plugin folder an included file names is relative to that file.
    if (part.contains("plugin_path") && part["plugin_path"].is_array())
      for (auto& p : part["plugin_path"])
        if (p.is_string() && std::filesystem::path(p.get<std::string>()).is_relative())
          p = (path.parent_path() / p.get<std::string>()).lexically_normal().string();
    fold(merged, prov, part, part_prov);
  }
  fold(merged, prov, root, own);
  prov.emplace("", std::make_pair(file, std::string()));
  return merged;
}

}  // namespace

std::string GraphDecl::where(const std::string& pointer) const {
  // The longest prefix of the pointer some file declared.
  for (std::string p = pointer;;) {
    auto it = provenance.find(p);
    if (it != provenance.end()) return at(it->second.first, it->second.second + pointer.substr(p.size()));
    if (p.empty()) break;
    p = p.substr(0, p.rfind('/'));
  }
  return at(file, pointer);
}

GraphDecl parse_graph_text(const std::string& text, const std::string& file, const std::vector<std::string>& sets,
                           const std::vector<std::string>& args) {
  Diagnostics d;
  std::vector<std::string> chain;
  {
    std::error_code ec;
    chain.push_back(std::filesystem::weakly_canonical(file, ec).string());
  }
  Provenance prov;
  json root = compose(text, file, chain, prov, d);
  GraphDecl g;
  g.file = file;
  g.name = std::filesystem::path(file).stem().string();
  if (prov.size() > 1) g.provenance = prov;  // composed: errors name the file that declared the value
  Ctx c{file, d, &g};
  if (!c.expect(root, json::value_t::object, "object", "")) d.raise_if_any();

  apply_args(root, args, file, d);
  SetOrigins origin;
  apply_sets(root, sets, d, origin);

  c.only_keys(root, {"name", "description", "nodes", "wires", "clock", "transport", "live", "processes", "plugin_path"}, "");
  if (root.contains("name") && c.expect(root["name"], json::value_t::string, "string", "/name"))
    g.name = root["name"].get<std::string>();
  if (root.contains("description") && c.expect(root["description"], json::value_t::string, "string", "/description"))
    g.description = root["description"].get<std::string>();

  if (!root.contains("nodes")) {
    c.err("", "missing key \"nodes\"");
  } else if (c.expect(root["nodes"], json::value_t::object, "object", "/nodes")) {
    if (root["nodes"].empty()) c.err("/nodes", "a graph needs at least one node");
    for (auto it = root["nodes"].begin(); it != root["nodes"].end(); ++it) {
      const std::string ptr = "/nodes/" + pointer_escape(it.key());
      if (!is_identifier(it.key())) {
        c.err("/nodes/" + pointer_escape(quoted_name(it.key())), "node name \"" + quoted_name(it.key()) + "\" must be letters, digits and _ (not starting with a digit), at most " +
                        std::to_string(kMaxNameLength) + " characters");
        continue;
      }
      if (auto nd = parse_node(it.key(), it.value(), origin, c)) g.nodes.emplace(it.key(), std::move(*nd));
    }
  }

  if (root.contains("wires") && c.expect(root["wires"], json::value_t::array, "array", "/wires")) {
    for (std::size_t i = 0; i < root["wires"].size(); ++i) {
      const std::string ptr = "/wires/" + std::to_string(i);
      const json& w = root["wires"][i];
      if (!c.expect(w, json::value_t::object, "object", ptr)) continue;
      c.only_keys(w, {"from", "to"}, ptr);
      if (!w.contains("from")) c.err(ptr, "missing key \"from\"");
      if (!w.contains("to")) c.err(ptr, "missing key \"to\"");
      if (!w.contains("from") || !w.contains("to")) continue;
      auto from = parse_endpoint(w["from"], ptr + "/from", c);
      // "to" is one endpoint or a list of them (fan-out from one output).
      if (w["to"].is_array()) {
        if (w["to"].empty()) c.err(ptr + "/to", "empty list: name at least one \"node.port\"");
        for (std::size_t k = 0; k < w["to"].size(); ++k) {
          auto to = parse_endpoint(w["to"][k], ptr + "/to/" + std::to_string(k), c);
          if (from && to) g.wires.push_back({*from, *to, i, "/" + std::to_string(k)});
        }
      } else {
        auto to = parse_endpoint(w["to"], ptr + "/to", c);
        if (from && to) g.wires.push_back({*from, *to, i, ""});
      }
    }
  }
  if (root.contains("clock")) parse_clock(root["clock"], g, c);
  if (root.contains("transport")) parse_transport(root["transport"], g, c);
  if (root.contains("live")) parse_live(root["live"], g, c);
  if (root.contains("processes")) parse_processes(root["processes"], g, c);
  if (!g.transport.security.empty() && g.transport.security != kSecurityOff && std::filesystem::path(g.transport.security).is_relative())
    g.transport.security = (std::filesystem::path(file).parent_path() / g.transport.security).lexically_normal().string();
  if (root.contains("plugin_path")) {
    parse_string_list(root["plugin_path"], g.plugin_path, "/plugin_path", c);
    auto base = std::filesystem::path(file).parent_path();
    for (auto& p : g.plugin_path)
      if (std::filesystem::path(p).is_relative()) p = (base / p).lexically_normal().string();
  }
  d.raise_if_any();
  return g;
}

const ProcessDecl& process_policy(const GraphDecl& g, const std::string& process) {
  static const ProcessDecl kDefault;
  auto it = g.processes.find(process);
  return it == g.processes.end() ? kDefault : it->second;
}

GraphDecl load_graph_file(const std::string& path, const std::vector<std::string>& sets, const std::vector<std::string>& args) {
  std::string text, why;
  if (!read_graph_text(path, text, why)) throw InvalidInput(path, why == "does not exist" ? "no such file" : why);
  return parse_graph_text(text, path, sets, args);
}

}  // namespace brickyard::fw
