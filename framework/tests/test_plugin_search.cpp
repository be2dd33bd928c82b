// The plugin search order: an earlier folder's plugin overrides a later one of the same name,
// with a notice naming both libraries; two providers of one name in one folder stay an error.
// The impostor is tests/fixtures/duplicate.cpp: a library whose plugin is named
// testing.transform (version 9.9.9), like the testing plugin's.
#include "loader/registry.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>

using namespace brickyard::fw;
namespace fs = std::filesystem;

namespace {

const std::string kImpostorDir = std::string(BRICKYARD_TEST_FIXTURE_DIR) + "/duplicate";
const std::string kPluginDir = BRICKYARD_TEST_PLUGIN_DIR;

std::string all_problems(const Registry& r) {
  std::string s;
  for (const auto& lp : r.problems())
    for (const auto& p : lp.problems) s += lp.library + ": " + p + "\n";
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Sets an environment variable for a scope, then puts back what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

TEST(PluginSearch, EarlierFolderOverridesLaterWithNotice) {
  Registry r;
  r.add_directory(kImpostorDir);  // --plugin-path
  r.add_directory(kPluginDir);    // the built-in folder
  EXPECT_TRUE(r.problems().empty()) << all_problems(r);
  const PluginEntry* p = r.find("testing.transform");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->manifest.version, "9.9.9");
  EXPECT_TRUE(ends_with(p->library, "/libfixture_duplicate.so")) << p->library;
  // Listed once, and the later folder's other plugins are all there.
  std::size_t listed = 0;
  for (const auto& e : r.plugins()) listed += e.manifest.name == "testing.transform";
  EXPECT_EQ(listed, 1u);
  EXPECT_TRUE(r.find("testing.scripted_source"));
  ASSERT_EQ(r.notices().size(), 1u);
  const std::string& n = r.notices()[0];
  EXPECT_EQ(n.rfind("plugin 'testing.transform' from " + kImpostorDir + "/libfixture_duplicate.so overrides the one in ", 0), 0u) << n;
  EXPECT_TRUE(ends_with(n, "/libtesting_transform.so")) << n;
}

TEST(PluginSearch, OverrideFollowsTheOrderNotTheLibrary) {
  Registry r;
  r.add_directory(kPluginDir);
  r.add_directory(kImpostorDir);
  EXPECT_TRUE(r.problems().empty()) << all_problems(r);
  const PluginEntry* p = r.find("testing.transform");
  ASSERT_TRUE(p);
  EXPECT_NE(p->manifest.version, "9.9.9");
  EXPECT_TRUE(ends_with(p->library, "/libtesting_transform.so")) << p->library;
  ASSERT_EQ(r.notices().size(), 1u);
  EXPECT_TRUE(ends_with(r.notices()[0], "overrides the one in " + kImpostorDir + "/libfixture_duplicate.so")) << r.notices()[0];
}

TEST(PluginSearch, SameFolderDuplicateIsAnError) {
  // One folder holding both providers (links to the two libraries).
  const fs::path dir = fs::path(testing::TempDir()) / "brickyard_plugin_search_same_folder";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::create_symlink(kImpostorDir + "/libfixture_duplicate.so", dir / "libfixture_duplicate.so");
  fs::create_symlink(kPluginDir + "/libtesting_transform.so", dir / "libtesting_transform.so");
  Registry r;
  r.add_directory(dir.string());
  ASSERT_EQ(r.problems().size(), 1u) << all_problems(r);
  EXPECT_EQ(r.problems()[0].library, (dir / "libtesting_transform.so").string());
  ASSERT_EQ(r.problems()[0].problems.size(), 1u);
  EXPECT_EQ(r.problems()[0].problems[0],
            "plugin 'testing.transform' is also provided by " + (dir / "libfixture_duplicate.so").string());
  EXPECT_TRUE(r.notices().empty());
  fs::remove_all(dir);
}

TEST(PluginSearch, SameLibraryInTwoFoldersIsNoOverride) {
  // A folder named twice (--plugin-path and the built-in one) loads each library once.
  Registry r;
  r.add_directory(kPluginDir);
  r.add_directory(kPluginDir);
  EXPECT_TRUE(r.problems().empty()) << all_problems(r);
  EXPECT_TRUE(r.notices().empty());
}

TEST(PluginSearch, OrderIsCommandLineGraphEnvironmentBuiltIn) {
  ScopedEnv env("BRICKYARD_PLUGIN_PATH", "/env/one::/env/two");
  const auto dirs = plugin_search_dirs({"/cli/a", "/cli/b"}, {"/graph/a"});
  ASSERT_GE(dirs.size(), 5u);
  EXPECT_EQ(std::vector<std::string>(dirs.begin(), dirs.begin() + 5),
            (std::vector<std::string>{"/cli/a", "/cli/b", "/graph/a", "/env/one", "/env/two"}));
  // Then at most the folder beside the executable.
  ASSERT_LE(dirs.size(), 6u);
  if (dirs.size() == 6) {
    EXPECT_TRUE(ends_with(dirs[5], "lib/brickyard/plugins")) << dirs[5];
  }
}
