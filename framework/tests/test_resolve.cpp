// Resolution against the real testing plugins, loaded the way the host loads them.
#include "graph/diagnostics.hpp"
#include "graph/resolve.hpp"
#include "test_registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace brickyard::fw;

namespace {

const Registry& registry() { return test::testing_plugins(); }

std::vector<Diagnostic> errors(const std::string& text, const std::vector<std::string>& sets = {}) {
  static std::vector<GraphDecl> keep;  // resolve keeps pointers into the declaration
  try {
    keep.push_back(parse_graph_text(text, "g.json", sets));
    resolve_graph(keep.back(), registry());
  } catch (const InvalidInput& e) {
    return e.diagnostics();
  }
  return {};
}

bool has(const std::vector<Diagnostic>& d, const std::string& where, const std::string& what) {
  for (const auto& x : d)
    if (x.where == where && x.message.find(what) != std::string::npos) return true;
  return false;
}

std::string chain(const std::string& extra_nodes = "", const std::string& extra_wires = "") {
  return R"({"nodes": {"src": {"plugin": "testing.scripted_source", "params": {"rate_hz": 50}},
                       "t": {"plugin": "testing.transform"},
                       "sink": {"plugin": "testing.assert_sink"})" +
         extra_nodes + R"(},
            "wires": [{"from": "src.out", "to": "t.in"}, {"from": "t.out", "to": "sink.in"})" +
         extra_wires + "]}";
}

}  // namespace

TEST(Resolve, RegistryLoadedTestingPlugins) {
  EXPECT_TRUE(registry().problems().empty());
  EXPECT_TRUE(registry().find("testing.scripted_source"));
  EXPECT_TRUE(registry().find("testing.blob_source"));
  EXPECT_TRUE(registry().find("testing.blob_sink"));
}

TEST(Resolve, ValidChainDefaultsAndScheduleOrder) {
  auto g = parse_graph_text(chain(), "g.json");
  auto rg = resolve_graph(g, registry());
  ASSERT_EQ(rg.nodes.size(), 3u);
  // Upstream first, whatever the names.
  EXPECT_EQ(rg.nodes[0].decl->name, "src");
  EXPECT_EQ(rg.nodes[1].decl->name, "t");
  EXPECT_EQ(rg.nodes[2].decl->name, "sink");
  EXPECT_EQ(rg.nodes[0].period_ns, 20'000'000);
  EXPECT_DOUBLE_EQ(rg.nodes[1].params.number("gain"), 1.0);
  EXPECT_TRUE(rg.nodes[1].trigger_inputs.count("in"));
}

TEST(Resolve, SimPeriodRoundedToStep) {
  auto g = parse_graph_text(chain(), "g.json", {"src.rate_hz=3"});
  auto rg = resolve_graph(g, registry());
  EXPECT_EQ(rg.nodes[0].period_ns, 333'000'000);
}

TEST(Resolve, ParamErrors) {
  EXPECT_TRUE(has(errors(chain(), {"src.rate_hz=\"fast\""}), "g.json#/nodes/src/params/rate_hz", "expected number"));
  EXPECT_TRUE(has(errors(chain(), {"src.rate_hz=0"}), "g.json#/nodes/src/params/rate_hz", "expected a value from 0.001"));
  EXPECT_TRUE(has(errors(chain(), {"src.rat_hz=1"}), "g.json#/nodes/src/params/rat_hz", "unknown parameter \"rat_hz\""));
  EXPECT_TRUE(has(errors(chain(), {"t.fault=\"sometimes\""}), "g.json#/nodes/t/params/fault", "expected one of"));
  EXPECT_TRUE(has(errors(chain(R"(, "b": {"plugin": "testing.blob_source"})")), "g.json#/nodes/b/params",
                  "missing required parameter \"size_bytes\""));
  EXPECT_TRUE(has(errors(chain(), {"src.count=1.5"}), "g.json#/nodes/src/params/count", "expected integer"));
}

TEST(Resolve, ConstraintsBetweenParams) {
  // testing.assert_sink binds min_value <= max_value: the pointer names the value the graph set.
  EXPECT_TRUE(has(errors(chain(R"(, "s2": {"plugin": "testing.assert_sink", "params": {"min_value": 3, "max_value": 1}})",
                               R"(, {"from": "t.out", "to": "s2.in"})")),
                  "g.json#/nodes/s2/params/max_value", "parameter 'min_value' (3) must be at most 'max_value' (1)"));
  EXPECT_TRUE(has(errors(chain(), {"sink.min_rate_hz=5", "sink.max_rate_hz=4"}), "g.json#/nodes/sink/params/max_rate_hz",
                  "must be at most 'max_rate_hz' (4) (from --set sink.max_rate_hz=4)"));
  // Equal bounds keep the order; a NaN (off) bound keeps every order.
  EXPECT_TRUE(errors(chain(), {"sink.min_value=5", "sink.max_value=5"}).empty());
  EXPECT_TRUE(errors(chain(), {"sink.min_value=5"}).empty());
}

TEST(Resolve, WireErrors) {
  EXPECT_TRUE(has(errors(chain("", R"(, {"from": "src.outt", "to": "sink.in"})")), "g.json#/wires/2/from", "has no port \"outt\""));
  EXPECT_TRUE(has(errors(chain("", R"(, {"from": "nope.out", "to": "sink.in"})")), "g.json#/wires/2/from", "no node named"));
  EXPECT_TRUE(has(errors(chain("", R"(, {"from": "sink.in", "to": "t.in"})")), "g.json#/wires/2/from", "is an input"));
  EXPECT_TRUE(has(errors(chain("", R"(, {"from": "src.out", "to": "sink.in"})")), "g.json#/wires/2/to", "already has a writer"));
  EXPECT_TRUE(has(errors(chain(R"(, "b": {"plugin": "testing.blob_source", "params": {"size_bytes": 1}}, "s2": {"plugin": "testing.assert_sink"})",
                               R"(, {"from": "b.out", "to": "s2.in"})")),
                  "g.json#/wires/2", "type mismatch"));
  EXPECT_TRUE(has(errors(chain(R"(, "s2": {"plugin": "testing.assert_sink"})")), "g.json#/nodes/s2", "is not wired"));
}

TEST(Resolve, ZeroDelayCycleRejectedDelayedCycleAccepted) {
  const std::string cyc = R"({"nodes": {"a": {"plugin": "testing.transform"}, "b": {"plugin": "testing.transform"}},
    "wires": [{"from": "a.out", "to": "b.in"}, {"from": "b.out", "to": "a.in"}]})";
  EXPECT_TRUE(has(errors(cyc), "g.json#/wires", "zero-delay cycle"));
}

TEST(Resolve, ProcessSelection) {
  std::string split = R"({"clock": {"mode": "real"}, "nodes": {"src": {"plugin": "testing.scripted_source", "process": "a"},
    "sink": {"plugin": "testing.assert_sink", "process": "b"}}, "wires": [{"from": "src.out", "to": "sink.in"}]})";
  auto g = parse_graph_text(split, "g.json");
  auto rg = resolve_graph(g, registry(), "b");
  ASSERT_EQ(rg.nodes.size(), 1u);
  EXPECT_EQ(rg.nodes[0].decl->name, "sink");
  try {
    resolve_graph(g, registry(), "c");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.diagnostics()[0].where, "--process c");
  }
}

// Issue 20: a value no car could use (1e308 for a rate, a size, a distance) is refused before
// anything runs. Every project plugin declares both bounds of every number it takes...
TEST(ParamBounds, EveryProjectPluginBoundsItsNumbers) {
  std::vector<std::string> unbounded;
  for (const auto& p : registry().plugins())
    for (const auto& s : p.manifest.params)
      if ((s.type == brickyard::ParamType::number || s.type == brickyard::ParamType::integer ||
           s.type == brickyard::ParamType::number_array) &&
          (!s.min || !s.max || !std::isfinite(*s.min) || !std::isfinite(*s.max)))
        unbounded.push_back(p.manifest.name + "." + s.name);
  EXPECT_GT(registry().plugins().size(), 10u);
  EXPECT_TRUE(unbounded.empty()) << "numbers without both bounds: " << ::testing::PrintToString(unbounded);
}

// ...and where a plugin (a third party's) declares none, the framework's ±1e9 holds.
TEST(ParamBounds, AnUndeclaredBoundIsTheFrameworks) {
  brickyard::ParamValue out;
  auto open = brickyard::ParamSpec::number("gain", 1).at_least(0);
  EXPECT_EQ(convert_param(open, nlohmann::json(1e9), out), "");
  EXPECT_NE(convert_param(open, nlohmann::json(1e308), out).find("from 0 to 1e+09 (the framework's bound"),
            std::string::npos);
  auto none = brickyard::ParamSpec::integer("count", 1);
  EXPECT_NE(convert_param(none, nlohmann::json(-2000000000), out).find("from -1e+09 to 1e+09"), std::string::npos);
  auto declared = brickyard::ParamSpec::number("big", 1).range(0, 1e12);
  EXPECT_EQ(convert_param(declared, nlohmann::json(1e11), out), "");
  EXPECT_NE(convert_param(brickyard::ParamSpec::numbers("xs", {}), nlohmann::json::parse("[1, 1e300]"), out)
                .find("element 1"),
            std::string::npos);
}

// A split graph on the sim clock (exec/lockstep.hpp): one process's resolution keeps every node,
// in the one schedule order, the others' not `here`; restarts and foreign writers are refused.
TEST(Resolve, SimSplitKeepsEveryNodeInOneOrder) {
  static std::vector<GraphDecl> keep;
  const std::string text = R"({"nodes": {"src": {"plugin": "testing.scripted_source", "process": "a"},
    "double": {"plugin": "testing.transform", "process": "b"}, "check": {"plugin": "testing.assert_sink", "process": "a"}},
    "wires": [{"from": "src.out", "to": "double.in"}, {"from": "double.out", "to": "check.in"}]})";
  keep.push_back(parse_graph_text(text, "g.json"));
  const ResolvedGraph all = resolve_graph(keep.back(), registry());
  const ResolvedGraph a = resolve_graph(keep.back(), registry(), "a");
  EXPECT_FALSE(all.lockstep);
  ASSERT_TRUE(a.lockstep);
  ASSERT_EQ(a.nodes.size(), all.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].decl->name, all.nodes[i].decl->name);
    EXPECT_EQ(a.nodes[i].order, i);
    EXPECT_EQ(a.nodes[i].here, a.nodes[i].decl->process == "a");
  }
  const std::string real = R"({"nodes": {"src": {"plugin": "testing.scripted_source", "process": "a"},
    "check": {"plugin": "testing.assert_sink", "process": "b"}}, "wires": [{"from": "src.out", "to": "check.in"}], "clock": {"mode": "real"}})";
  keep.push_back(parse_graph_text(real, "r.json"));
  const ResolvedGraph ra = resolve_graph(keep.back(), registry(), "a");
  EXPECT_FALSE(ra.lockstep);
  EXPECT_EQ(ra.nodes.size(), 1u);
  const std::string restart = R"({"nodes": {"src": {"plugin": "testing.scripted_source", "process": "a"},
    "check": {"plugin": "testing.assert_sink", "process": "b"}}, "wires": [{"from": "src.out", "to": "check.in"}],
    "processes": {"b": {"restart": "on-failure", "may_die": true}}, "transport": {"foreign_writers": "accept"}})";
  const auto e = errors(restart);
  EXPECT_TRUE(has(e, "g.json#/processes/b/restart", "needs the real clock"));
  EXPECT_TRUE(has(e, "g.json#/processes/b/may_die", "needs the real clock"));
  EXPECT_TRUE(has(e, "g.json#/transport/foreign_writers", "needs the real clock"));
}

// A node that neither the graph nor its plugin gives a step deadline gets one from its trigger
// (issue 44): ten of its periods, at least 0.5 s; a data-triggered node's period is its writer's.
TEST(Resolve, DeadlinesDerivedFromTheTriggerUnlessSet) {
  struct D {
    double s;
    bool derived, by_graph;
    bool operator==(const D& o) const { return s == o.s && derived == o.derived && by_graph == o.by_graph; }
  };
  auto deadlines = [](const std::string& text) {
    static std::vector<GraphDecl> keep;
    keep.push_back(parse_graph_text(text, "g.json"));
    std::map<std::string, D> out;
    for (const auto& n : resolve_graph(keep.back(), registry()).nodes) out[n.decl->name] = {n.deadline_s, n.deadline_derived, n.deadline_by_graph};
    return out;
  };
  auto slow = deadlines(R"({"nodes": {"src": {"plugin": "testing.scripted_source", "params": {"rate_hz": 4}},
                                      "t": {"plugin": "testing.transform"}, "sink": {"plugin": "testing.assert_sink"}},
                            "wires": [{"from": "src.out", "to": "t.in"}, {"from": "t.out", "to": "sink.in"}]})");
  EXPECT_TRUE((slow["src"] == D{2.5, true, false}));   // 10 x 0.25 s
  EXPECT_TRUE((slow["t"] == D{2.5, true, false}));     // stepped by src's samples
  EXPECT_TRUE((slow["sink"] == D{2.5, true, false}));  // and down the chain
  auto fast = deadlines(chain());                      // 50 Hz: 0.2 s, below the floor
  EXPECT_TRUE((fast["src"] == D{0.5, true, false}));
  EXPECT_TRUE((fast["sink"] == D{0.5, true, false}));
  // Set by the graph node, or by the plugin's parameter in the graph: the graph's, not derived.
  auto set = deadlines(R"({"nodes": {"src": {"plugin": "testing.scripted_source", "params": {"rate_hz": 4}, "deadline_s": 0.3},
                                     "f": {"plugin": "testing.fault", "params": {"step_deadline_s": 0.7}},
                                     "g": {"plugin": "testing.fault"}, "sink": {"plugin": "testing.assert_sink"}},
                           "wires": [{"from": "src.out", "to": "sink.in"}]})");
  EXPECT_TRUE((set["src"] == D{0.3, false, true}));
  EXPECT_TRUE((set["f"] == D{0.7, false, true}));
  EXPECT_TRUE((set["g"] == D{0.5, true, false}));  // its parameter's default 0: derived
  EXPECT_TRUE((set["sink"] == D{2.5, true, false})) << "its writer's period, not the writer's deadline";
}
