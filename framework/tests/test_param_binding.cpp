// The SDK's typed parameter binding: one declaration gives the manifest's spec and the read.
#include <brickyard/plugin.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard;

namespace {

enum class Side { left, right };

struct Inner {
  float tolerance = 0.35f;
  int min_size = 2, max_size = 100;
};

struct Settings {
  bool enabled = true;
  std::int64_t count = -1;
  std::uint32_t small = 7;
  double gain = 1.5;
  std::string name = "ims";
  std::vector<double> mount = {1.0, 0.5, 0.25};
  std::optional<double> limit;
  std::string doc = R"({"a":1})";
  Side side = Side::right;
  Inner inner;
  double deg_in_rad = 0.1;
  std::string file;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("enabled", &Settings::enabled);
  b.bind("count", &Settings::count).at_least(-1);
  b.bind("small", &Settings::small);
  b.bind("gain", &Settings::gain).in_unit("m").range(0, 10).doc("a gain");
  b.bind("name", &Settings::name).one_of({"ims", "monza"});
  b.bind("mount", &Settings::mount);
  b.bind("limit", &Settings::limit);
  b.bind_json("doc", &Settings::doc);
  b.bind_choice("side", {{"left", Side::left}, {"right", Side::right}}, &Settings::side);
  b.bind("tolerance", &Settings::inner, &Inner::tolerance);
  b.bind("min_size", &Settings::inner, &Inner::min_size);
  b.bind("max_size", &Settings::inner, &Inner::max_size);
  b.bind_with(ParamSpec::number("deg", 5.0).in_unit("deg"),
              [](const Params& p, Settings& s) { s.deg_in_rad = p.number("deg") * M_PI / 180; });
  b.bind_required("file", &Settings::file);
  b.declare(ParamSpec::number("rate_hz", 10));
  b.not_above("min_size", "max_size");
  return b;
}

Manifest manifest() { return Manifest("test.bound", "1.0.0").parameters(bindings()); }

// The values the host would pass: every default, plus the graph's.
Params host_params(const Manifest& m, std::map<std::string, ParamValue> set = {}) {
  Params p;
  for (const auto& s : m.params)
    if (s.default_value) p.set(s.name, *s.default_value);
  for (auto& [k, v] : set) p.set(k, v);
  return p;
}

}  // namespace

TEST(ParamBinding, TypesAndDefaultsComeFromTheMembers) {
  const Manifest m = manifest();
  ASSERT_EQ(m.params.size(), 15u);
  auto spec = [&](const char* n) { return *m.param_spec(n); };
  EXPECT_EQ(spec("enabled").type, ParamType::boolean);
  EXPECT_EQ(std::get<bool>(*spec("enabled").default_value), true);
  EXPECT_EQ(spec("count").type, ParamType::integer);
  EXPECT_EQ(std::get<std::int64_t>(*spec("count").default_value), -1);
  EXPECT_EQ(spec("small").type, ParamType::integer);
  EXPECT_EQ(spec("gain").type, ParamType::number);
  EXPECT_EQ(std::get<double>(*spec("gain").default_value), 1.5);
  EXPECT_EQ(spec("gain").unit, "m");
  EXPECT_EQ(*spec("gain").max, 10);
  EXPECT_EQ(spec("gain").description, "a gain");
  EXPECT_EQ(spec("name").type, ParamType::string);
  EXPECT_EQ(spec("name").choices.size(), 2u);
  EXPECT_EQ(spec("mount").type, ParamType::number_array);
  EXPECT_EQ(std::get<std::vector<double>>(*spec("mount").default_value), (std::vector<double>{1.0, 0.5, 0.25}));
  EXPECT_EQ(spec("limit").type, ParamType::number);
  EXPECT_TRUE(std::isnan(std::get<double>(*spec("limit").default_value)));  // an empty optional: off
  EXPECT_EQ(spec("doc").type, ParamType::json);
  EXPECT_EQ(spec("side").type, ParamType::string);
  EXPECT_EQ(std::get<std::string>(*spec("side").default_value), "right");
  EXPECT_EQ((spec("side").choices), (std::vector<std::string>{"left", "right"}));
  // A float default is declared as the decimal that reads back as the same float.
  EXPECT_EQ(std::get<double>(*spec("tolerance").default_value), 0.35);
  EXPECT_TRUE(spec("file").required());
  EXPECT_EQ(m.constraints.size(), 1u);
}

TEST(ParamBinding, ReadFillsEveryBoundMember) {
  const Manifest m = manifest();
  const Settings s = bindings().read(host_params(m, {{"enabled", false},
                                                     {"count", std::int64_t{12}},
                                                     {"small", std::int64_t{3}},
                                                     {"gain", 2.5},
                                                     {"name", std::string("monza")},
                                                     {"mount", std::vector<double>{3, 2, 1}},
                                                     {"limit", 4.0},
                                                     {"doc", JsonText{"[1,2]"}},
                                                     {"side", std::string("left")},
                                                     {"tolerance", 0.5},
                                                     {"max_size", std::int64_t{9}},
                                                     {"deg", 180.0},
                                                     {"file", std::string("x.csv")}}));
  EXPECT_FALSE(s.enabled);
  EXPECT_EQ(s.count, 12);
  EXPECT_EQ(s.small, 3u);
  EXPECT_EQ(s.gain, 2.5);
  EXPECT_EQ(s.name, "monza");
  EXPECT_EQ(s.mount, (std::vector<double>{3, 2, 1}));
  ASSERT_TRUE(s.limit);
  EXPECT_EQ(*s.limit, 4.0);
  EXPECT_EQ(s.doc, "[1,2]");
  EXPECT_EQ(s.side, Side::left);
  EXPECT_EQ(s.inner.tolerance, 0.5f);
  EXPECT_EQ(s.inner.min_size, 2);
  EXPECT_EQ(s.inner.max_size, 9);
  EXPECT_DOUBLE_EQ(s.deg_in_rad, M_PI);
  EXPECT_EQ(s.file, "x.csv");
}

TEST(ParamBinding, DefaultsReadBackBitForBit) {
  const Settings d;
  const Settings s = bindings().read(host_params(manifest(), {{"file", std::string("f")}}));
  EXPECT_EQ(s.inner.tolerance, d.inner.tolerance);  // 0.35f through the decimal 0.35
  EXPECT_FALSE(s.limit);                           // NaN: off
  EXPECT_EQ(s.side, d.side);
  EXPECT_EQ(s.mount, d.mount);
}

TEST(ParamBinding, MissingValuesKeepTheDefaultsStruct) {
  const Settings s = bindings().read(Params{});  // a unit test passes only what it changes
  EXPECT_EQ(s.gain, 1.5);
  EXPECT_EQ(s.deg_in_rad, 0.1);
}

TEST(ParamBinding, ConstraintsAreCheckedByRead) {
  const Manifest m = manifest();
  try {
    bindings().read(host_params(m, {{"min_size", std::int64_t{50}}, {"max_size", std::int64_t{10}}}));
    FAIL() << "min above max was accepted";
  } catch (const BadInput& e) {
    EXPECT_STREQ(e.what(), "parameter 'min_size' (50) must be at most 'max_size' (10)");
  }
  EXPECT_NO_THROW(bindings().read(host_params(m, {{"min_size", std::int64_t{10}}, {"max_size", std::int64_t{10}}})));
}

TEST(ParamBinding, StrictConstraintAndNaNBounds) {
  ParamConstraint below{"lo", "hi", true};
  Params p;
  p.set("lo", 1.0);
  p.set("hi", 1.0);
  EXPECT_EQ(below.violation(p), "parameter 'lo' (1) must be below 'hi' (1)");
  p.set("hi", std::nan(""));  // an optional bound that is off keeps every order
  EXPECT_EQ(below.violation(p), "");
  p.set("hi", std::int64_t{2});  // integers compare as numbers
  EXPECT_EQ(below.violation(p), "");
}

TEST(ParamBinding, PluginMistakesAreCaughtWhenTheManifestIsBuilt) {
  ParamBinding<Settings> b;
  b.bind("gain", &Settings::gain);
  EXPECT_THROW(b.bind("gain", &Settings::gain), std::logic_error);  // bound twice
  // A default that is none of the choices.
  EXPECT_THROW(b.bind_choice("side", {{"left", Side::left}}, &Settings::side), std::logic_error);
}
