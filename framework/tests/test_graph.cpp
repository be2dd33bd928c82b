#include "graph/diagnostics.hpp"
#include "graph/graph.hpp"
#include "graph/json_scan.hpp"

#include <gtest/gtest.h>
#include <cstdlib>
#include <fstream>
#include <filesystem>

using namespace brickyard::fw;

namespace {

std::string first_error(const std::string& text, const std::vector<std::string>& sets = {},
                        const std::vector<std::string>& args = {}) {
  try {
    parse_graph_text(text, "g.json", sets, args);
  } catch (const InvalidInput& e) {
    return e.diagnostics().front().where + ": " + e.diagnostics().front().message;
  }
  return "";
}

const char* kMinimal = R"({"nodes": {"a": {"plugin": "testing.scripted_source"}}})";

}  // namespace

TEST(JsonScan, PositionCountsLinesAndColumns) {
  auto p = position_of("ab\ncd\nef", 4);
  EXPECT_EQ(p.line, 2u);
  EXPECT_EQ(p.column, 2u);
}

TEST(JsonScan, DepthLimitIgnoresBracketsInStrings) {
  EXPECT_FALSE(find_excess_depth(R"({"a": "[[[[[[[[[["})", 3));
  auto f = find_excess_depth("[[[[1]]]]", 3);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->offset, 3u);
}

TEST(JsonScan, DuplicateKeysPerObjectOnly) {
  EXPECT_FALSE(find_duplicate_key(R"({"a": {"x": 1}, "b": {"x": 2}})"));
  EXPECT_FALSE(find_duplicate_key(R"({"a": ["a", "a"]})"));
  auto f = find_duplicate_key("{\"a\": 1,\n \"a\": 2}");
  ASSERT_TRUE(f);
  EXPECT_EQ(position_of("{\"a\": 1,\n \"a\": 2}", f->offset).line, 2u);
}

TEST(GraphParse, Minimal) {
  auto g = parse_graph_text(kMinimal, "dir/minimal.json");
  EXPECT_EQ(g.name, "minimal");
  ASSERT_EQ(g.nodes.size(), 1u);
  EXPECT_EQ(g.nodes.at("a").process, kDefaultProcess);
  EXPECT_TRUE(g.clock.sim);
  EXPECT_EQ(g.transport.interfaces, std::vector<std::string>{"127.0.0.1"});
}

TEST(GraphParse, SyntaxErrorHasLineAndColumn) {
  EXPECT_EQ(first_error("{\n  \"nodes\": {,\n}").substr(0, 11), "g.json:2:13");
}

TEST(GraphParse, ANumberNoDoubleHoldsIsNamedWithItsPlace) {
  EXPECT_EQ(first_error("{\"nodes\": {\"a\": {\"plugin\": \"x.y\",\n \"params\": {\"rate_hz\": 1e999}}}}"),
            "g.json:2:24: number 1e999 is beyond what a double holds");
}

TEST(GraphParse, DuplicateNodeNamed) {
  auto e = first_error("{\"nodes\": {\"a\": {\"plugin\": \"x.y\"},\n \"a\": {\"plugin\": \"x.y\"}}}");
  EXPECT_NE(e.find("g.json:2:2"), std::string::npos) << e;
  EXPECT_NE(e.find("duplicate key \"a\""), std::string::npos) << e;
}

TEST(GraphParse, DeepNestingRejectedWithoutRecursion) {
  std::string deep(200000, '[');
  EXPECT_NE(first_error(deep).find("nesting deeper than"), std::string::npos);
}

TEST(GraphParse, ErrorsNameJsonPointers) {
  EXPECT_EQ(first_error("[]"), "g.json#: expected object, found array");
  EXPECT_EQ(first_error(R"({"nodes": []})"), "g.json#/nodes: expected object, found array");
  EXPECT_NE(first_error(R"({"nodes": {"a": {"plugin": 3}}})").find("g.json#/nodes/a/plugin: expected string"), std::string::npos);
  EXPECT_NE(first_error(R"({"nodes": {"a": {"plugin": "x.y", "parms": {}}}})").find("#/nodes/a/parms: unknown key"),
            std::string::npos);
  EXPECT_NE(first_error(R"({"nodes": {"a": {"plugin": "x.y"}}, "wires": [{"from": "a", "to": "b.c"}]})")
                .find("#/wires/0/from: expected \"node.port\""),
            std::string::npos);
  EXPECT_NE(first_error(R"({"nodes": {"a": {"plugin": "x.y"}}, "clock": {"mode": "fast"}})").find("#/clock/mode"),
            std::string::npos);
}

TEST(GraphParse, AllErrorsReportedTogether) {
  try {
    parse_graph_text(R"({"nodes": {"a": {"plugin": 1}}, "clock": {"step_s": -1}, "extra": 1})", "g.json");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.diagnostics().size(), 3u) << e.what();
  }
}

TEST(GraphParse, ProcessPolicies) {
  const char* text = R"({"nodes": {"a": {"plugin": "x.y", "process": "stack"}, "b": {"plugin": "x.y", "process": "sim"}},
    "processes": {"stack": {"restart": "on-failure", "max_restarts": 5, "backoff_s": 0.25, "may_die": true}},
    "transport": {"startup_timeout_s": 3}})";
  auto g = parse_graph_text(text, "g.json");
  const ProcessDecl& stack = process_policy(g, "stack");
  EXPECT_EQ(stack.restart, ProcessDecl::Restart::on_failure);
  EXPECT_EQ(stack.max_restarts, 5);
  EXPECT_DOUBLE_EQ(stack.backoff_s, 0.25);
  EXPECT_TRUE(stack.may_die);
  // A process the section does not name: never restarted, may not die.
  EXPECT_EQ(process_policy(g, "sim").restart, ProcessDecl::Restart::never);
  EXPECT_FALSE(process_policy(g, "sim").may_die);
  EXPECT_DOUBLE_EQ(g.transport.startup_timeout_s, 3);
  EXPECT_EQ(first_error(R"({"nodes": {"a": {"plugin": "x.y"}}, "processes": {"main": {"max_restarts": -1}}})"),
            "g.json#/processes/main/max_restarts: expected an integer from 0 to 1000, found -1");
  EXPECT_EQ(first_error(R"({"nodes": {"a": {"plugin": "x.y"}}, "processes": {"main": {"may_die": "yes"}}})"),
            "g.json#/processes/main/may_die: expected boolean, found string");
  EXPECT_EQ(first_error(R"({"nodes": {"a": {"plugin": "x.y"}}, "processes": {"other": {}}})"),
            "g.json#/processes/other: no node runs in process \"other\"");
}

TEST(GraphParse, SetSwapsAPlugin) {
  auto g = parse_graph_text(kMinimal, "g.json", {"a.plugin=testing.blob_source", "a.rate_hz=5"});
  EXPECT_EQ(g.nodes.at("a").plugin, "testing.blob_source");
  EXPECT_EQ(g.nodes.at("a").plugin_origin, "--set a.plugin=testing.blob_source");
  EXPECT_EQ(g.nodes.at("a").params.at("rate_hz"), 5);
  EXPECT_FALSE(g.nodes.at("a").params.contains("plugin"));
}

TEST(GraphParse, SetOverridesParams) {
  auto g = parse_graph_text(kMinimal, "g.json", {"a.rate_hz=25", "a.values=[1,2]", "a.mode=fast"});
  const auto& p = g.nodes.at("a").params;
  EXPECT_EQ(p["rate_hz"], 25);
  EXPECT_EQ(p["values"], nlohmann::json::parse("[1,2]"));
  EXPECT_EQ(p["mode"], "fast");
  EXPECT_EQ(g.nodes.at("a").param_origin.at("rate_hz"), "--set a.rate_hz=25");
}

TEST(GraphParse, SetErrors) {
  EXPECT_EQ(first_error(kMinimal, {"a.rate_hz"}), "--set a.rate_hz: expected node.param=value");
  EXPECT_EQ(first_error(kMinimal, {"b.x=1"}), "--set b.x=1: the graph has no node \"b\"");
}

// A graph's named arguments: defaults, --arg, a whole-string use keeps the value's type, a use
// inside text splices it in, and --set still has the last word.
TEST(GraphArgs, DefaultsArgsAndTypes) {
  const char* text = R"({"args": {"track": "tracks/IMS.csv", "laps": 2, "pylons": [], "side": "right"},
    "nodes": {"a": {"plugin": "testing.scripted_source",
      "params": {"track": "${track}", "laps": "${laps}", "pylons": "${pylons}", "note": "${laps} laps of ${track}", "n": 1}}},
    "wires": [{"from": "a.out", "to": "b.wall_${side}"}]})";
  auto g = parse_graph_text(text, "g.json");
  const auto& p = g.nodes.at("a").params;
  EXPECT_EQ(p["track"], "tracks/IMS.csv");
  EXPECT_EQ(p["laps"], 2);
  EXPECT_TRUE(p["pylons"].is_array());
  EXPECT_EQ(p["note"], "2 laps of tracks/IMS.csv");
  EXPECT_EQ(g.wires.at(0).to.port, "wall_right");
  auto h = parse_graph_text(text, "g.json", {"a.laps=5"}, {"track=tracks/Monza.csv", "laps=3", "pylons=[{\"s\": 40, \"d\": 1}]", "side=left"});
  const auto& q = h.nodes.at("a").params;
  EXPECT_EQ(q["track"], "tracks/Monza.csv");
  EXPECT_EQ(q["laps"], 5);  // --set after --arg
  EXPECT_EQ(q["pylons"].at(0)["s"], 40);
  EXPECT_EQ(q["note"], "3 laps of tracks/Monza.csv");
  EXPECT_EQ(h.wires.at(0).to.port, "wall_left");
}

TEST(GraphArgs, Errors) {
  const char* text = R"({"args": {"track": "x.csv", "list": [1]}, "nodes": {"a": {"plugin": "p.q", "params": {"t": "${track}", "u": "${nope}", "v": "at ${list}"}}}})";
  try {
    parse_graph_text(text, "g.json", {}, {"trak=y.csv", "oops"});
    FAIL() << "accepted";
  } catch (const InvalidInput& e) {
    std::vector<std::string> all;
    for (const auto& d : e.diagnostics()) all.push_back(d.where + ": " + d.message);
    ASSERT_EQ(all.size(), 4u);
    EXPECT_EQ(all[0], "--arg trak=y.csv: the graph declares no argument \"trak\" (declared: list, track)");
    EXPECT_EQ(all[1], "--arg oops: expected name=value");
    EXPECT_EQ(all[2], "g.json#/nodes/a/params/u: argument \"nope\" is used but the graph's \"args\" does not declare it");
    EXPECT_EQ(all[3], "g.json#/nodes/a/params/v: argument \"list\" is array: only a string, a number or a boolean can stand inside text");
  }
  EXPECT_EQ(first_error(R"({"args": [1], "nodes": {"a": {"plugin": "p.q"}}})"), "g.json#/args: expected an object of argument names and default values, found array");
  EXPECT_EQ(first_error(kMinimal, {}, {"x=1"}), "--arg x=1: the graph declares no argument \"x\" (declared: none)");
}

TEST(GraphParse, PluginPathRelativeToGraphFile) {
  auto g = parse_graph_text(R"({"plugin_path": ["build", "/abs"], "nodes": {"a": {"plugin": "x.y"}}})", "/p/q/g.json");
  EXPECT_EQ(g.plugin_path, (std::vector<std::string>{"/p/q/build", "/abs"}));
}

namespace {
// Files in a fresh temporary folder, for graphs that include graphs.
struct TempGraphs {
  std::filesystem::path dir;
  TempGraphs() {
    char t[] = "/tmp/by_compose_XXXXXX";
    dir = mkdtemp(t);
  }
  ~TempGraphs() { std::filesystem::remove_all(dir); }
  std::string put(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};
std::string load_error(const std::string& path) {
  try {
    load_graph_file(path);
  } catch (const InvalidInput& e) {
    return e.diagnostics().front().where + ": " + e.diagnostics().front().message;
  }
  return "";
}
const char* kBase = R"({"nodes": {"src": {"plugin": "testing.scripted_source", "params": {"rate_hz": 50, "count": 10}},
  "check": {"plugin": "testing.assert_sink", "params": {"min_count": 10}}},
  "wires": [{"from": "src.out", "to": "check.in"}], "clock": {"mode": "sim", "duration_s": 1}})";
}  // namespace

// A graph includes another and overrides what it declares: a param one by one, a node added, a
// wire appended; the clock's duration only.
TEST(GraphCompose, IncludesAreFoldedInOrderAndOverridden) {
  TempGraphs t;
  t.put("base.json", kBase);
  const std::string top = t.put("top.json", R"({"include": ["base.json"],
    "nodes": {"src": {"params": {"rate_hz": 100}}, "more": {"plugin": "testing.assert_sink"}},
    "wires": [{"from": "src.out", "to": "more.in"}], "clock": {"duration_s": 2}})");
  const GraphDecl g = load_graph_file(top);
  EXPECT_EQ(g.nodes.at("src").plugin, "testing.scripted_source");
  EXPECT_EQ(g.nodes.at("src").params.at("rate_hz"), 100);
  EXPECT_EQ(g.nodes.at("src").params.at("count"), 10);
  EXPECT_EQ(g.nodes.size(), 3u);
  ASSERT_EQ(g.wires.size(), 2u);
  EXPECT_EQ(g.wires[1].to.node, "more");
  EXPECT_TRUE(g.clock.sim);
  EXPECT_DOUBLE_EQ(*g.clock.duration_s, 2);
  // Each value named in the file that declared it, at its pointer there.
  EXPECT_EQ(g.where("/nodes/src/params/rate_hz"), top + "#/nodes/src/params/rate_hz");
  EXPECT_EQ(g.where("/nodes/src/params/count"), (t.dir / "base.json").string() + "#/nodes/src/params/count");
  EXPECT_EQ(g.where("/wires/1/to"), top + "#/wires/0/to");
  EXPECT_EQ(g.where("/wires/0/from"), (t.dir / "base.json").string() + "#/wires/0/from");
}

TEST(GraphCompose, ErrorsNameTheFileThatDeclaredTheValue) {
  TempGraphs t;
  t.put("base.json", kBase);
  const std::string base = (t.dir / "base.json").string();
  EXPECT_EQ(load_error(t.put("a.json", R"({"include": "base.json", "clock": {"mode": "fast"}})")),
            (t.dir / "a.json").string() + "#/clock/mode: expected \"sim\" or \"real\", found \"fast\"");
  t.put("bad_base.json", R"({"nodes": {"src": {"plugin": "testing.scripted_source", "parms": {}}}})");
  EXPECT_EQ(load_error(t.put("b.json", R"({"include": ["bad_base.json"]})")).substr(0, (t.dir / "bad_base.json").string().size() + 21),
            (t.dir / "bad_base.json").string() + "#/nodes/src/parms: un");
  EXPECT_EQ(load_error(t.put("c.json", R"({"include": ["base.json"], "wires": [{"from": "src", "to": "check.in"}]})")),
            (t.dir / "c.json").string() + "#/wires/0/from: expected \"node.port\", found \"src\"");
  EXPECT_EQ(load_error(t.put("d.json", R"({"include": ["nope.json"]})")),
            (t.dir / "d.json").string() + "#/include/0: included file " + (t.dir / "nope.json").string() + ": does not exist");
  (void)base;
}

TEST(GraphCompose, AnIncludeCycleIsRefusedNamed) {
  TempGraphs t;
  const std::string a = t.put("a.json", R"({"include": ["b.json"], "nodes": {"x": {"plugin": "testing.scripted_source"}}})");
  t.put("b.json", R"({"include": ["a.json"]})");
  const std::string e = load_error(a);
  EXPECT_NE(e.find("b.json#/include/0: an include cycle: "), std::string::npos) << e;
  EXPECT_NE(e.find("a.json includes " + (t.dir / "b.json").string() + " includes " + (t.dir / "a.json").string()), std::string::npos) << e;
}
