#include "graph/resolve.hpp"

#include "graph/diagnostics.hpp"

#include "transport/wire_types.hpp"
#include <brickyard/roles.hpp>

#include <cmath>
#include <map>
#include <queue>
#include <sstream>

namespace brickyard::fw {
namespace {

using nlohmann::json;

std::string fmt_num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A bound a plugin did not declare is the framework's: no parameter value beyond 1e9 in
// magnitude (a graph or `--set` giving 1e308 to a "rate" or a "size" once made runs allocate
// until bad_alloc; docs/graph-format.md). The project's own plugins declare both bounds of every
// number (ParamBounds.EveryProjectPluginBoundsItsNumbers).
constexpr double kDefaultBound = 1e9;

std::string range_error(const ParamSpec& spec, double v) {
  const double lo = spec.min.value_or(-kDefaultBound), hi = spec.max.value_or(kDefaultBound);
  if (v < lo || v > hi || !std::isfinite(v)) {
    std::string r = "from " + fmt_num(lo) + " to " + fmt_num(hi);
    if (!spec.min || !spec.max) r += " (the framework's bound where the plugin declares none)";
    return "expected a value " + r + (spec.unit.empty() ? "" : " " + spec.unit) + ", found " + fmt_num(v);
  }
  return {};
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

}  // namespace

std::string convert_param(const ParamSpec& spec, const json& v, ParamValue& out) {
  auto found = [&] { return std::string(", found ") + v.dump(); };
  switch (spec.type) {
    case ParamType::boolean:
      if (!v.is_boolean()) return "expected boolean" + found();
      out = v.get<bool>();
      return {};
    case ParamType::integer: {
      if (!v.is_number_integer()) return "expected integer" + found();
      auto i = v.get<std::int64_t>();
      if (auto e = range_error(spec, static_cast<double>(i)); !e.empty()) return e;
      out = i;
      return {};
    }
    case ParamType::number: {
      if (!v.is_number()) return "expected number" + found();
      double d = v.get<double>();
      if (auto e = range_error(spec, d); !e.empty()) return e;
      out = d;
      return {};
    }
    case ParamType::string: {
      if (!v.is_string()) return "expected string" + found();
      auto s = v.get<std::string>();
      if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(), s) == spec.choices.end())
        return "expected one of " + join(spec.choices) + found();
      out = s;
      return {};
    }
    case ParamType::number_array: {
      if (!v.is_array()) return "expected array of numbers" + found();
      std::vector<double> a;
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number()) return "expected array of numbers; element " + std::to_string(i) + " is " + v[i].dump();
        double d = v[i].get<double>();
        if (auto e = range_error(spec, d); !e.empty()) return "element " + std::to_string(i) + ": " + e;
        a.push_back(d);
      }
      out = std::move(a);
      return {};
    }
    case ParamType::json:
      out = JsonText{v.dump()};
      return {};
  }
  return "unsupported parameter type";
}

const ResolvedNode* ResolvedGraph::node(const std::string& name) const {
  for (const auto& n : nodes)
    if (n.decl->name == name) return &n;
  return nullptr;
}

namespace {

// The steps of resolve_graph, in order, over the state they share.
class Resolver {
 public:
  Resolver(const GraphDecl& g, const Registry& reg, const std::string& process, const NodeChecks& checks)
      : g_(g), reg_(reg), process_(process), checks_(checks) { rg_.decl = &g; }

  ResolvedGraph run() {
    report_library_problems();
    for (const auto& [name, nd] : g_.nodes) resolve_node(name, nd);
    type_outputs_by_parameter();
    for (const auto& w : g_.wires) resolve_wire(w);
    check_required_inputs();
    check_zero_delay_cycles();
    check_processes();
    if (!d_.empty()) run_plugin_checks();
    d_.raise_if_any();
    order_schedule();
    return std::move(rg_);
  }

 private:
  void err(const std::string& ptr, const std::string& msg) { d_.add(g_.where(ptr), msg); }

  // Libraries that failed to load are errors: a broken plugin install is never ignored.
  void report_library_problems() {
    for (const auto& lp : reg_.problems()) {
      std::string all;
      for (const auto& p : lp.problems) all += (all.empty() ? "" : "; ") + p;
      d_.add(lp.library, all);
    }
  }

  void resolve_node(const std::string& name, const NodeDecl& nd) {
    const std::size_t errors_before = d_.items().size();
    resolve_node_parts(name, nd);
    if (d_.items().size() != errors_before) faulty_.insert(name);
  }

  // The plugins' own checks of the nodes that resolved cleanly, beside the graph's errors.
  void run_plugin_checks() {
    if (!checks_) return;
    ResolvedGraph partial;
    partial.decl = &g_;
    partial.wire_types = rg_.wire_types;
    partial.output_types = rg_.output_types;
    for (const auto& [name, rn] : by_name_) {
      if (faulty_.count(name)) continue;
      partial.nodes.push_back(rn);
      partial.nodes.back().here = process_.empty() || rn.decl->process == process_;
    }
    for (const auto& f : checks_(partial)) d_.add(f.where, f.message);
  }

  void resolve_node_parts(const std::string& name, const NodeDecl& nd) {
    const std::string ptr = "/nodes/" + pointer_escape(name);
    rg_.processes.insert(nd.process);
    ResolvedNode rn;
    rn.decl = &nd;
    rn.plugin = reg_.find(nd.plugin);
    if (!rn.plugin) {
      std::vector<std::string> known;
      for (const auto& p : reg_.plugins()) known.push_back(p.manifest.name);
      err(ptr + "/plugin", "unknown plugin \"" + nd.plugin + "\"" + (nd.plugin_origin.empty() ? "" : " (from " + nd.plugin_origin + ")") +
                               " (known: " + join(known) + "; searched " + join(reg_.directories()) + ")");
      return;
    }
    check_roles(nd, rn.plugin->manifest, ptr);
    resolve_params(nd, rn, ptr);
    resolve_triggers(rn, ptr);
    resolve_latency(rn, ptr);
    resolve_deadline(nd, rn, ptr);
    by_name_.emplace(name, std::move(rn));
  }

  // The roles the node's plugin must play: the graph's "role", and when --set swapped the plugin,
  // every role the replaced one played. Each names what the plugin lacks of it.
  void check_roles(const NodeDecl& nd, const Manifest& m, const std::string& ptr) {
    std::vector<std::string> wanted;
    if (!nd.role.empty()) wanted.push_back(nd.role);
    if (const PluginEntry* old = nd.replaced_plugin.empty() ? nullptr : reg_.find(nd.replaced_plugin))
      for (const auto& r : old->manifest.roles)
        if (r != nd.role) wanted.push_back(r);
    const std::string from = nd.plugin_origin.empty() ? "" : " (from " + nd.plugin_origin + ")";
    for (const auto& r : wanted) {
      const RoleContract* role = find_role(r);
      if (!role || plays(m, r)) continue;  // an unknown role is the graph's error, reported with it
      std::string why;
      for (const auto& w : role_mismatches(m, *role)) why += (why.empty() ? ": " : "; ") + w;
      if (why.empty()) why = " (its ports fit; the plugin does not declare it plays the role)";
      err(ptr + (nd.plugin_origin.empty() && nd.role == r ? "/role" : "/plugin"),
          "plugin " + m.name + " of node '" + nd.name + "' does not play role '" + r + "'" + why + from);
    }
  }

  void resolve_params(const NodeDecl& nd, ResolvedNode& rn, const std::string& ptr) {
    const Manifest& m = rn.plugin->manifest;
    const std::string& name = nd.name;
    // Params: unknown, wrong type, out of range, missing. A node whose plugin --set swapped keeps
    // the file's params the new plugin has, and leaves those it has not, said (the planner swap
    // of a race graph is one flag); a param given by --set must be the new plugin's.
    std::vector<std::string> left;
    for (auto it = nd.params.begin(); it != nd.params.end(); ++it) {
      std::string pptr = ptr + "/params/" + pointer_escape(it.key());
      auto o = nd.param_origin.find(it.key());
      std::string from = o == nd.param_origin.end() ? "" : " (from " + o->second + ")";
      const ParamSpec* spec = m.param_spec(it.key());
      if (!spec && !nd.plugin_origin.empty() && o == nd.param_origin.end()) {
        left.push_back(it.key());
        continue;
      }
      if (!spec) {
        std::vector<std::string> names;
        for (const auto& p : m.params) names.push_back(p.name);
        err(pptr, "unknown parameter \"" + it.key() + "\" of plugin " + m.name + " (parameters: " + join(names) + ")" + from);
        continue;
      }
      ParamValue v;
      if (auto e = convert_param(*spec, it.value(), v); !e.empty())
        err(pptr, e + from);
      else
        rn.params.set(spec->name, std::move(v));
    }
    if (!left.empty())
      rg_.notices.push_back("node '" + name + "' runs " + m.name + " (" + nd.plugin_origin + "): the file's " + join(left) +
                            (left.size() > 1 ? " are not its parameters" : " is not its parameter") + ", left out");
    for (const auto& spec : m.params) {
      if (rn.params.has(spec.name)) continue;
      if (spec.default_value)
        rn.params.set(spec.name, *spec.default_value);
      else
        err(ptr + "/params", "missing required parameter \"" + spec.name + "\" (" + to_string(spec.type) + ") of plugin " + m.name);
    }
    // Constraints between parameters (a minimum above its maximum), once every value is known.
    // The pointer names the one the graph set (the later of the two when both), else /params.
    for (const auto& c : m.constraints) {
      const std::string e = c.violation(rn.params);
      if (e.empty()) continue;
      std::string culprit = nd.params.contains(c.upper) ? c.upper : nd.params.contains(c.lower) ? c.lower : "";
      auto o = nd.param_origin.find(culprit);
      std::string from = o == nd.param_origin.end() ? "" : " (from " + o->second + ")";
      err(ptr + "/params" + (culprit.empty() ? "" : "/" + pointer_escape(culprit)), e + from);
    }
  }

  void resolve_triggers(ResolvedNode& rn, const std::string& ptr) {
    const Manifest& m = rn.plugin->manifest;
    for (const auto& t : m.triggers) {
      if (t.kind == TriggerSpec::Kind::on_input) {
        rn.trigger_inputs.insert(t.ref);
      } else if (t.kind == TriggerSpec::Kind::periodic && rn.params.has(t.ref)) {
        double hz = rn.params.number(t.ref);
        if (!(hz > 0) || !std::isfinite(hz)) {
          err(ptr + "/params/" + t.ref, "rate must be positive, found " + fmt_num(hz));
          continue;
        }
        // The sim clock runs in whole steps: a period is rounded to a multiple of clock.step_s.
        double step_ns = g_.clock.step_s * 1e9;
        std::int64_t steps = std::max<std::int64_t>(1, std::llround(1e9 / hz / step_ns));
        rn.period_ns =
            g_.clock.sim ? static_cast<std::int64_t>(std::llround(steps * step_ns)) : static_cast<std::int64_t>(std::llround(1e9 / hz));
      }
    }
  }

  void resolve_latency(ResolvedNode& rn, const std::string& ptr) {
    const Manifest& m = rn.plugin->manifest;
    // A modelled latency: the sim scheduler runs the step beside what follows it and delivers its
    // outputs later, which needs a step done before the next one: a periodic node's latency at
    // most its period; a node woken by its inputs is woken by what came meanwhile once its step
    // is done (sim_scheduler.cpp). Not both: a timer due while the step is out would have to wait.
    for (const auto& t : m.triggers) {
      if (t.kind != TriggerSpec::Kind::latency || !rn.params.has(t.ref)) continue;
      const double s = rn.params.number(t.ref);
      const std::string at = ptr + "/params/" + pointer_escape(t.ref);
      if (!(s >= 0) || !std::isfinite(s)) {
        err(at, "latency must be zero or more seconds, found " + fmt_num(s));
        continue;
      }
      if (s == 0 || !g_.clock.sim) continue;  // the real clock's latency is the real one
      const double step_ns = g_.clock.step_s * 1e9;
      const std::int64_t ns = static_cast<std::int64_t>(std::llround(std::llround(s * 1e9 / step_ns) * step_ns));
      const bool on_input = !rn.trigger_inputs.empty();
      if ((rn.period_ns > 0) == on_input)
        err(at, "a latency needs a node that steps on its rate alone or on its inputs alone (plugin " + m.name +
                    (on_input ? " steps on both)" : " steps on neither)"));
      else if (on_input) {
        rn.latency_ns = ns;
        if (ns > 0) input_latency_at_.push_back(at);
      }
      else if (ns > rn.period_ns)
        err(at, "latency " + fmt_num(s) + " s is longer than the node's period (" + fmt_num(rn.period_ns * 1e-9) +
                    " s): a step's outputs must be delivered before its next step");
      else
        rn.latency_ns = ns;
    }
  }

  void resolve_deadline(const NodeDecl& nd, ResolvedNode& rn, const std::string& ptr) {
    const Manifest& m = rn.plugin->manifest;
    // The step deadline: the plugin's parameter (manifest default, graph params), unless the node's deadline_s says.
    // Set by the graph (its deadline_s, or the parameter in its params or a --set) it is the
    // graph's choice, held on the sim clock too; the plugin's own default is a default.
    rn.deadline_s = nd.deadline_s;
    rn.deadline_by_graph = nd.deadline_s > 0;
    for (const auto& t : m.triggers) {
      if (t.kind != TriggerSpec::Kind::deadline || !rn.params.has(t.ref) || nd.deadline_s > 0) continue;
      const double s = rn.params.number(t.ref);
      if (!(s >= 0 && s <= 3600)) {
        err(ptr + "/params/" + pointer_escape(t.ref), "a step deadline must be 0 (derived from the trigger) to 3600 seconds, found " + fmt_num(s));
      } else {
        rn.deadline_s = s;
        rn.deadline_by_graph = s > 0 && nd.params.contains(t.ref);
      }
    }
  }

  void type_outputs_by_parameter() {
    // Outputs of any type whose type the graph names by the parameter the plugin gives for it
    // (Manifest::output_any(port, doc, param)): typed ports from here on.
    for (const auto& [name, rn] : by_name_)
      for (const auto& p : rn.plugin->manifest.ports) {
        if (p.direction != PortDirection::output || !is_any_message_type(p.type_name) || p.type_name.size() == 1) continue;
        const std::string param = p.type_name.substr(1);
        if (!rn.params.has(param)) continue;
        const std::string type = rn.params.string(param);
        if (type.empty()) continue;
        const auto* entry = find_wire_type(type);
        if (!entry) {
          err("/nodes/" + pointer_escape(name) + "/params/" + pointer_escape(param), "no message type \"" + type + "\" in this build");
          continue;
        }
        PortSpec typed = p;
        typed.type_name = type;
        typed.type_hash = entry->hash;
        named_type_[name + "." + p.name] = typed;
        rg_.output_types[name + "." + p.name] = type;
      }
  }

  // The port at one end of a wire (k 0: from, 1: to), or null when there is none (reported; a node
  // whose plugin is unknown was reported with it).
  const PortSpec* wire_end(const WireDecl& w, int k) {
    const Endpoint& end = k ? w.to : w.from;
    const std::string where = k ? w.to_ptr() : "/wires/" + std::to_string(w.index) + "/from";
    if (!g_.nodes.count(end.node)) {
      err(where, "no node named \"" + end.node + "\"");
      return nullptr;
    }
    auto rit = by_name_.find(end.node);
    if (rit == by_name_.end()) return nullptr;
    const Manifest& m = rit->second.plugin->manifest;
    if (const auto nt = named_type_.find(end.text()); k == 0 && nt != named_type_.end()) return &nt->second;
    if (const PortSpec* port = m.port(end.port)) return port;
    std::vector<std::string> names;
    for (const auto& p : m.ports) names.push_back(p.name + (p.direction == PortDirection::input ? " (input)" : " (output)"));
    err(where, "node \"" + end.node + "\" (" + m.name + ") has no port \"" + end.port + "\" (ports: " + join(names) + ")");
    return nullptr;
  }

  void resolve_wire(const WireDecl& w) {
    const std::string ptr = "/wires/" + std::to_string(w.index);
    const PortSpec* ports[2] = {wire_end(w, 0), wire_end(w, 1)};
    if (!ports[0] || !ports[1]) return;
    bool ok = true;
    if (ports[0]->direction != PortDirection::output) {
      err(ptr + "/from", "\"" + w.from.text() + "\" is an input; a wire goes from an output");
      ok = false;
    }
    if (ports[1]->direction != PortDirection::input) {
      err(w.to_ptr(), "\"" + w.to.text() + "\" is an output; a wire goes to an input");
      ok = false;
    }
    if (!ok) return;
    // A port of any type takes the type of the port at the wire's other end: an input, its
    // writer's; an output, its readers' (one type for all of them).
    const bool any_in = ports[1]->type_name == kAnyMessageType, any_out = is_any_message_type(ports[0]->type_name);
    if (any_in && any_out) {
      err(w.to_item.empty() ? ptr : w.to_ptr(),
          w.from.text() + " and " + w.to.text() + " both take any message type: nothing says which" +
              (ports[0]->type_name.size() > 1 ? " (set " + w.from.node + "'s parameter '" + ports[0]->type_name.substr(1) + "')" : ""));
      return;
    }
    if (any_out) {
      auto [ot, fresh_type] = rg_.output_types.emplace(w.from.text(), ports[1]->type_name);
      if (!fresh_type && ot->second != ports[1]->type_name) {
        err(w.to_item.empty() ? ptr : w.to_ptr(), "type mismatch: " + w.from.text() + " (any type) already feeds " + ot->second + ", " +
                                                      w.to.text() + " takes " + ports[1]->type_name);
        return;
      }
    }
    const bool any = any_in || any_out;
    if (!any && (ports[0]->type_name != ports[1]->type_name || ports[0]->type_hash != ports[1]->type_hash)) {
      err(w.to_item.empty() ? ptr : w.to_ptr(),
          "type mismatch: " + w.from.text() + " carries " + ports[0]->type_name + ", " + w.to.text() + " takes " + ports[1]->type_name);
      return;
    }
    auto [it, fresh] = writer_of_.emplace(w.to.text(), w.to_ptr());
    if (!fresh) {
      err(w.to_ptr(), "input \"" + w.to.text() + "\" already has a writer (" + it->second + "); an input takes one wire");
      return;
    }
    writer_node_[w.to.text()] = w.from.node;
    rg_.wire_types[w.to.text()] = any_out ? ports[1]->type_name : ports[0]->type_name;
    downstream_[w.from.node].insert(w.to.node);
    if (by_name_.at(w.to.node).trigger_inputs.count(w.to.port)) downstream_zero_delay_[w.from.node].insert(w.to.node);
  }

  void check_required_inputs() {
    for (const auto& [name, rn] : by_name_)
      for (const auto& p : rn.plugin->manifest.ports)
        if (p.direction == PortDirection::input && p.required && !writer_of_.count(name + "." + p.name))
          err("/nodes/" + pointer_escape(name),
              "required input \"" + p.name + "\" (" + p.type_name + ") of plugin " + rn.plugin->manifest.name + " is not wired");
  }

  void check_zero_delay_cycles() {
    // A cycle made only of input-triggered steps has no first step at one instant of sim time.
    // Depth first with a stack of our own: a chain of 100 000 nodes recursed past the thread's
    // stack.
    static const std::set<std::string> kNone;
    auto outs = [&](const std::string& n) -> const std::set<std::string>& {
      const auto it = downstream_zero_delay_.find(n);
      return it == downstream_zero_delay_.end() ? kNone : it->second;
    };
    std::map<std::string, int> color;  // 0 unseen, 1 on the path, 2 done
    std::vector<std::pair<const std::string*, std::set<std::string>::const_iterator>> path;
    bool found = false;
    for (const auto& [name, _] : by_name_) {
      if (found || color[name] != 0) continue;
      color[name] = 1;
      path.push_back({&name, outs(name).begin()});
      while (!path.empty() && !found) {
        auto& [n, it] = path.back();
        if (it == outs(*n).end()) {
          color[*n] = 2;
          path.pop_back();
          continue;
        }
        const std::string& m = *it++;
        if (color[m] == 1) {
          // Named whole when short; a long one by its first nodes and its length.
          std::string cyc;
          std::size_t len = 0;
          bool on = false;
          for (const auto& [p, unused] : path) {
            if (*p == m) on = true;
            if (on && ++len <= 8) cyc += *p + " -> ";
          }
          cyc += len <= 8 ? m : "… (" + std::to_string(len) + " nodes)";
          err("/wires",
              "zero-delay cycle " + cyc + ": every node in it steps on input, so nothing can go first (make one of them periodic)");
          found = true;
        } else if (color[m] == 0) {
          color[m] = 1;
          path.push_back({&m, outs(m).begin()});
        }
      }
    }
  }

  void check_processes() {
    if (!process_.empty()) {
      if (!rg_.processes.count(process_)) {
        std::vector<std::string> ps(rg_.processes.begin(), rg_.processes.end());
        d_.add("--process " + process_, "no node of the graph runs in process \"" + process_ + "\" (processes: " + join(ps) + ")");
      } else if (g_.clock.sim && rg_.processes.size() > 1) {
        rg_.lockstep = true;
      }
    }
    if (g_.clock.sim && rg_.processes.size() > 1) {
      // One sim clock across processes (exec/lockstep.hpp): every process replays the others' steps,
      // so none can restart or leave, and every sample must be the graph's writer's.
      for (const auto& [name, p] : g_.processes) {
        if (p.restart == ProcessDecl::Restart::on_failure)
          d_.add(g_.where("/processes/" + pointer_escape(name) + "/restart"),
                 "on-failure needs the real clock: a process of a split run on the sim clock cannot rejoin its lockstep");
        if (p.may_die)
          d_.add(g_.where("/processes/" + pointer_escape(name) + "/may_die"),
                 "needs the real clock: on the sim clock every process of a split run steps in lockstep with the others");
      }
      // A step that waits for its latency holds what comes to it meanwhile: the processes that
      // replay it would have to hold it too (exec/lockstep.hpp does not yet).
      for (const std::string& at : input_latency_at_)
        err(at, "a latency on a node woken by its inputs needs the graph in one process on the sim clock (a split run "
                "in lockstep does not replay it yet)");
      if (g_.transport.accept_foreign_writers)
        d_.add(g_.where("/transport/foreign_writers"),
               "accept needs the real clock: a split run on the sim clock takes each sample from its graph's writer alone");
    }
  }

  void order_schedule() {
    // Schedule order: upstream before downstream (Kahn), ties and cycles broken by name; the nodes
    // ready kept sorted, so a graph of 100 000 nodes orders in a fraction of a second (a scan of
    // every node per pick never finished).
    std::map<std::string, int> indeg;
    for (const auto& [n, _] : by_name_) indeg[n] = 0;
    for (const auto& [n, outs] : downstream_)
      for (const auto& m : outs)
        if (m != n) ++indeg[m];
    std::set<std::string> ready, remaining;
    for (const auto& [n, k] : indeg) {
      remaining.insert(n);
      if (k == 0) ready.insert(n);
    }
    while (!remaining.empty()) {
      // A (delayed) cycle when none is ready: the first remaining by name.
      const std::string pick = ready.empty() ? *remaining.begin() : *ready.begin();
      ready.erase(pick);
      remaining.erase(pick);
      for (const auto& m : downstream_[pick])
        if (m != pick && --indeg[m] == 0 && remaining.count(m)) ready.insert(m);
      derive_deadline(pick);
      const bool here = process_.empty() || by_name_.at(pick).decl->process == process_;
      if (here || rg_.lockstep) {
        ResolvedNode rn = by_name_.at(pick);
        rn.order = rg_.nodes.size();
        rn.here = here;
        rg_.nodes.push_back(std::move(rn));
      }
    }
  }

  // A node that neither its graph node nor its plugin gives a step deadline gets one from its
  // trigger (docs/reliability.md, "Deadlines by default"): ten of the periods its steps come at,
  // at least half a second; 2 s when no period is known. Called upstream first (the schedule's
  // order), so a data-triggered node's writers have their periods already.
  void derive_deadline(const std::string& name) {
    ResolvedNode& rn = by_name_.at(name);
    std::int64_t period = rn.period_ns;
    for (const auto& in : rn.trigger_inputs) {
      const auto w = writer_node_.find(name + "." + in);
      const auto p = w == writer_node_.end() ? trigger_period_.end() : trigger_period_.find(w->second);
      if (p != trigger_period_.end() && p->second > 0 && (period == 0 || p->second < period)) period = p->second;
    }
    trigger_period_[name] = period;
    if (rn.deadline_s > 0) return;
    rn.deadline_s = period > 0 ? std::max(kDefaultDeadlinePeriods * static_cast<double>(period) * 1e-9, kDefaultDeadlineFloor_s)
                               : kDefaultDeadlineUnknown_s;
    rn.deadline_derived = true;
  }

  const GraphDecl& g_;
  const Registry& reg_;
  const std::string& process_;
  std::vector<std::string> input_latency_at_;  // the latency parameters of nodes woken by their inputs
  const NodeChecks& checks_;
  Diagnostics d_;
  std::set<std::string> faulty_;  // nodes with an error of their own (unknown plugin, bad parameter)
  ResolvedGraph rg_;
  std::map<std::string, ResolvedNode> by_name_;
  std::map<std::string, PortSpec> named_type_;                          // "node.port" of any type -> the port as the type a parameter names
  std::map<std::string, std::string> writer_of_;                        // "node.port" input -> pointer of its wire
  std::map<std::string, std::string> writer_node_;                      // "node.port" input -> the node writing it
  std::map<std::string, std::int64_t> trigger_period_;                  // node -> the period its steps come at (0: unknown)
  std::map<std::string, std::set<std::string>> downstream_zero_delay_;  // node -> data-triggered subscribers
  std::map<std::string, std::set<std::string>> downstream_;
};

}  // namespace

ResolvedGraph resolve_graph(const GraphDecl& g, const Registry& reg, const std::string& process, const NodeChecks& checks) {
  return Resolver(g, reg, process, checks).run();
}

}  // namespace brickyard::fw
