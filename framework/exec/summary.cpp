#include "exec/summary.hpp"
#include "exec/node_runtime.hpp"

namespace brickyard::fw {

nlohmann::json summary_json(const RunSummary& s, const GraphDecl& g, const RunOptions& opt, bool sim,
                            const nlohmann::json& recording, const std::vector<std::unique_ptr<NodeRuntime>>& nodes) {
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
  for (auto& n : nodes) {
    nlohmann::json nj;
    nj["plugin"] = n->plugin_name();
    nj["steps"] = n->steps;
    if (opt.profile) nj["step_wall_s"] = n->step_wall_s;
    nj["metrics"] = n->metrics;
    for (auto& in : n->inputs) {
      nj["inputs"][in->name()] = {{"received", in->received()}, {"dropped", in->dropped()}};
    }
    for (auto& o : n->outputs) nj["outputs"][o->name()] = {{"published", o->published()}};
    j["nodes"][n->name] = nj;
  }
  return j;
}

}  // namespace brickyard::fw
