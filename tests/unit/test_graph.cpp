#include "graph/diagnostics.hpp"
#include "graph/graph.hpp"
#include "graph/json_scan.hpp"

#include <gtest/gtest.h>

using namespace brickyard::fw;

namespace {

std::string first_error(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    parse_graph_text(text, "g.json", sets);
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

TEST(GraphParse, PluginPathRelativeToGraphFile) {
  auto g = parse_graph_text(R"({"plugin_path": ["build", "/abs"], "nodes": {"a": {"plugin": "x.y"}}})", "/p/q/g.json");
  EXPECT_EQ(g.plugin_path, (std::vector<std::string>{"/p/q/build", "/abs"}));
}
