// `brickyard security init GRAPH --out DIR`: a CA, an identity per process and one to observe,
// the signed governance and each identity's signed permissions from the graph's wires.
#include "cli/command_table.hpp"
#include "cli/load_registry.hpp"
#include "graph/resolve.hpp"
#include "security/security_files.hpp"

#include <cstdio>

namespace brickyard::fw::cli {

int cmd_security(const Args& a) {
  if (a.target != "init")
    usage_error(a.target.empty() ? "security" : "security " + a.target, "expected: brickyard security init GRAPH --out DIR [--protect sign|encrypt] [--days N]");
  if (a.more.size() != 1) usage_error("security init", "needs one graph file");
  if (a.out.empty()) usage_error("security init", "needs --out DIR (the folder the graph's transport.security names)");
  const GraphDecl g = load_graph_file(a.more[0], a.sets, a.args);
  Registry reg = load_registry(a, &g);
  const ResolvedGraph rg = resolve_graph(g, reg);
  security::InitOptions o;
  o.protection = a.protect == "encrypt" ? security::Protection::encrypt : security::Protection::sign;
  o.days = a.days;
  const auto r = security::init(rg, a.out, o);
  std::printf("security init: %s for %s (%s, valid %d days)%s\n", a.out.c_str(), a.more[0].c_str(),
              o.protection == security::Protection::encrypt ? "traffic encrypted" : "traffic signed", o.days,
              r.reused_ca ? ", the folder's CA kept" : ", a new CA");
  for (const auto& id : r.identities)
    std::printf("  identity %-20s %s\n", id.c_str(), id == security::kObserver ? "reads every topic, writes none (brickyard topic --security DIR)" : "");
  std::printf("the graph uses it with \"transport\": {\"security\": \"%s\"} (relative to the graph's folder); "
              "ca_key.pem signs: keep it off the car\n", a.out.c_str());
  return 0;
}

}  // namespace brickyard::fw::cli
