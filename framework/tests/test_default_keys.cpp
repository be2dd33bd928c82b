// A split run's keys when its graph names none (security/default_keys.hpp): one folder per graph
// and wiring, made once under the user's state folder and reused; tests/cli/foreign_writer.sh
// runs a graph so secured and attacks it.
#include "graph/diagnostics.hpp"
#include "graph/resolve.hpp"
#include "security/default_keys.hpp"
#include "security/documents.hpp"
#include "test_registry.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace brickyard::fw;
namespace fs = std::filesystem;

namespace {

const char* kSplit = R"({"name": "split", "clock": {"mode": "real"}, "nodes": {
    "src": {"plugin": "testing.scripted_source", "process": "a"},
    "sink": {"plugin": "testing.assert_sink", "process": "b"}},
  "wires": [{"from": "src.out", "to": "sink.in"}]})";

ResolvedGraph resolved(const GraphDecl& g) { return resolve_graph(g, test::testing_plugins()); }

// The state folder of these tests, empty.
fs::path fresh_state() {
  const fs::path dir = fs::temp_directory_path() / "brickyard_default_keys_unit";
  fs::remove_all(dir);
  ::setenv("XDG_STATE_HOME", dir.c_str(), 1);
  return dir;
}

}  // namespace

TEST(DefaultKeys, TheGraphSaysByDefaultOffOrAFolder) {
  EXPECT_EQ(security::security_choice(parse_graph_text(kSplit, "/x/g.json")), security::SecurityChoice::by_default);
  const GraphDecl off = parse_graph_text(R"({"nodes": {"src": {"plugin": "testing.scripted_source"}}, "transport": {"security": "off"}})", "/x/g.json");
  EXPECT_EQ(off.transport.security, "off");  // not a folder beside the graph
  EXPECT_EQ(security::security_choice(off), security::SecurityChoice::off);
  const GraphDecl folder = parse_graph_text(R"({"nodes": {"src": {"plugin": "testing.scripted_source"}}, "transport": {"security": "./off"}})", "/x/g.json");
  EXPECT_EQ(folder.transport.security, "/x/off");
  EXPECT_EQ(security::security_choice(folder), security::SecurityChoice::folder);
}

TEST(DefaultKeys, OneFolderForEveryProcessOfARunAnotherOnceTheWiresChange) {
  const fs::path state = fresh_state();
  const GraphDecl g = parse_graph_text(kSplit, "/x/g.json");
  const std::string dir = security::default_keys_dir(resolved(g));
  EXPECT_EQ(dir, security::default_keys_dir(resolved(parse_graph_text(kSplit, "/x/g.json"))));
  EXPECT_EQ(fs::path(dir).parent_path(), state / "brickyard" / "keys");
  EXPECT_EQ(fs::path(dir).filename().string().rfind("split-", 0), 0u);
  GraphDecl rewired = g;
  rewired.nodes["sink"].process = "a";
  rewired.nodes["src"].process = "b";
  EXPECT_NE(security::default_keys_dir(resolved(rewired)), dir);
  EXPECT_NE(security::default_keys_dir(resolved(parse_graph_text(kSplit, "/y/g.json"))), dir);
}

TEST(DefaultKeys, MadeOnceEncryptingThenReusedAndRemadeWhenAFileIsGone) {
  const fs::path state = fresh_state();
  const GraphDecl g = parse_graph_text(kSplit, "/x/g.json");  // the resolved graph points into it
  const ResolvedGraph rg = resolved(g);
  const auto first = security::ensure_default_keys(rg);
  EXPECT_TRUE(first.made);
  for (const char* id : {"a", "b", "observer"}) EXPECT_TRUE(fs::is_regular_file(fs::path(first.dir) / id / "key.pem")) << id;
  std::ifstream gov(fs::path(first.dir) / "governance.xml");
  std::stringstream text;
  text << gov.rdbuf();
  EXPECT_NE(text.str().find("<rtps_protection_kind>ENCRYPT</rtps_protection_kind>"), std::string::npos);
  EXPECT_EQ(fs::status(state / "brickyard" / "keys").permissions() & fs::perms::all, fs::perms::owner_all);
  const auto again = security::ensure_default_keys(rg);
  EXPECT_FALSE(again.made);
  EXPECT_EQ(again.dir, first.dir);
  fs::remove(fs::path(first.dir) / "b" / "key.pem");
  EXPECT_TRUE(security::ensure_default_keys(rg).made);
  EXPECT_TRUE(fs::is_regular_file(fs::path(first.dir) / "b" / "key.pem"));
  fs::remove_all(state);
}

TEST(DefaultKeys, NoStateFolderIsBadInputNamingTheGraph) {
  ::unsetenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  const std::string saved = home ? home : "";
  ::unsetenv("HOME");
  try {
    security::default_keys_dir(resolved(parse_graph_text(kSplit, "/x/g.json")));
    ADD_FAILURE() << "no state folder, yet a keys folder";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.diagnostics()[0].where, "/x/g.json#/transport/security");
    EXPECT_NE(e.diagnostics()[0].message.find("set HOME"), std::string::npos);
  }
  if (home) ::setenv("HOME", saved.c_str(), 1);
}

// A split run on the sim clock: each process writes its clock records and reads the others'.
TEST(DefaultKeys, ALockstepRunsPermissionsCarryTheClockTopics) {
  const auto access = security::access_of(resolved(parse_graph_text(R"({"nodes": {
      "src": {"plugin": "testing.scripted_source", "process": "a"},
      "sink": {"plugin": "testing.assert_sink", "process": "b"}},
    "wires": [{"from": "src.out", "to": "sink.in"}]})", "/x/g.json")));
  EXPECT_TRUE(access.at("a").publish.count("brickyard_clock/a"));
  EXPECT_TRUE(access.at("a").subscribe.count("brickyard_clock/b"));
  EXPECT_TRUE(access.at("b").publish.count("brickyard_clock/b"));
  EXPECT_TRUE(access.at("b").subscribe.count("brickyard_clock/a"));
  EXPECT_FALSE(access.at("a").subscribe.count("brickyard_clock/a"));
  EXPECT_FALSE(security::access_of(resolved(parse_graph_text(kSplit, "/x/g.json"))).at("a").publish.count("brickyard_clock/a"));
}
