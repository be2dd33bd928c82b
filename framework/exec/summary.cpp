#include "exec/summary.hpp"
#include "exec/node_runtime.hpp"

#include <algorithm>
#include <cstdio>

namespace brickyard::fw {

nlohmann::json summary_json(const RunSummary& s, const GraphDecl& g, const RunOptions& opt, bool sim,
                            const nlohmann::json& recording, const std::vector<std::unique_ptr<NodeRuntime>>& nodes,
                            std::int64_t end_ns) {
  nlohmann::json j;
  j["graph"] = g.name;
  j["graph_file"] = g.file;
  j["result"] = to_string(s.result);
  j["reason"] = s.reason;
  j["clock"] = sim ? "sim" : "real";
  j["seed"] = opt.seed;
  j["process"] = opt.process.empty() ? "all" : opt.process;
  j["sim_time_s"] = s.sim_time_s;
  j["wall_time_s"] = s.wall_time_s;
  if (!recording.is_null()) j["recording"] = recording;
  j["nodes"] = nlohmann::json::object();
  nlohmann::json stale = nlohmann::json::array();
  for (auto& n : nodes) {
    nlohmann::json nj;
    nj["plugin"] = n->plugin_name();
    nj["steps"] = n->steps;
    if (opt.profile) nj["step_wall_s"] = n->step_wall_s;
    nj["metrics"] = n->metrics;
    for (auto& in : n->inputs) {
      nj["inputs"][in->name()] = {{"received", in->received()}, {"dropped", in->dropped()}};
      const InputQueue::Gaps g = in->gaps();
      if (g.received >= 2) nj["inputs"][in->name()]["max_gap_s"] = static_cast<double>(g.max_gap_ns) * 1e-9;
      const bool now_stale = g.stale(end_ns);
      if (g.stale_episodes > 0 || now_stale)
        stale.push_back({{"input", n->name + "." + in->name()}, {"stale_episodes", g.stale_episodes + (now_stale ? 1 : 0)},
                         {"max_gap_s", static_cast<double>(std::max(g.max_gap_ns, now_stale ? end_ns - g.last_ns : 0)) * 1e-9},
                         {"usual_interval_s", static_cast<double>(g.usual_ns) * 1e-9}, {"stale_at_end", now_stale}});
    }
    for (auto& o : n->outputs) nj["outputs"][o->name()] = {{"published", o->published()}};
    j["nodes"][n->name] = nj;
  }
  if (!stale.empty()) j["stale_inputs"] = stale;
  return j;
}

std::string stale_inputs_text(const std::vector<std::unique_ptr<NodeRuntime>>& nodes, std::int64_t now_ns) {
  std::string out;
  for (const auto& n : nodes)
    for (const auto& in : n->inputs) {
      const InputQueue::Gaps g = in->gaps();
      if (!g.stale(now_ns)) continue;
      char b[48];
      std::snprintf(b, sizeof b, " %.1f s", static_cast<double>(now_ns - g.last_ns) * 1e-9);
      out += (out.empty() ? "" : ", ") + n->name + "." + in->name() + b;
    }
  return out;
}

}  // namespace brickyard::fw
