// Parameters (DESIGN.md §2): enumeration, set/get by dotted path from text, validation
// messages naming the path, registry of run-time sections, diff -> rebuild.

#include "params_fixtures.hpp"

#include <sylva/core/params.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using fixture::Scene;
using fixture::Terrain;

// The example of DESIGN.md §2, verbatim: the designated-initialiser syntax must compile.
struct ChunkLodSettings {
  float max_pixel_error = 1.0f;   // tau, screen-space geometric error bound [px]
  float morph_fraction  = 0.25f;  // share of an LOD range used to morph [0..1]
  template <class V> void visit(V& v) {
    v(max_pixel_error, "max_pixel_error", {.min = 0.05f, .max = 64.f, .unit = "px",
      .help = "Largest allowed projected height error"});
    v(morph_fraction, "morph_fraction", {.min = 0.f, .max = 1.f});
  }
};

std::string set_error(Scene& s, std::string_view path, std::string_view text) {
  sylva::Status st = sylva::set_param(s, path, text);
  EXPECT_FALSE(st.ok()) << path << "=" << text << " was accepted";
  return st.ok() ? std::string() : st.error().message;
}

TEST(Params, DesignExampleDescribes) {
  ChunkLodSettings s;
  const auto params = sylva::describe_params(s);
  ASSERT_EQ(params.size(), 2u);
  EXPECT_EQ(params[0].path, "max_pixel_error");
  EXPECT_EQ(params[0].type_name(), "float");
  EXPECT_FLOAT_EQ(static_cast<float>(params[0].info.min), 0.05f);
  EXPECT_EQ(params[0].info.max, 64.0);
  EXPECT_STREQ(params[0].info.unit, "px");
  EXPECT_STREQ(params[0].info.help, "Largest allowed projected height error");
  EXPECT_EQ(params[1].path, "morph_fraction");
  EXPECT_STREQ(params[1].info.unit, "");
  ASSERT_TRUE(sylva::set_param(s, "max_pixel_error", "2").ok());
  EXPECT_EQ(s.max_pixel_error, 2.0f);
}

TEST(Params, EnumerationListsEveryFieldInVisitOrderWithInfo) {
  Scene s;
  const auto params = sylva::describe_params(s);
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"terrain.max_pixel_error", "float"}, {"terrain.world_scale", "double"}, {"terrain.chunk_dim", "int32"},
      {"terrain.seed", "uint32"},          {"terrain.offset", "int64"},       {"terrain.hash", "uint64"},
      {"terrain.skirts", "bool"},          {"terrain.height_map", "string"},  {"terrain.criterion", "enum"},
      {"terrain.quality", "enum"},         {"terrain.uv_scale", "vec2"},      {"terrain.sun_dir", "vec3"},
      {"terrain.tint", "vec4"},            {"terrain.tiles", "ivec2"},        {"terrain.origin", "dvec3"},
      {"terrain.grid", "uvec3"},           {"terrain.lod.morph_fraction", "float"},
      {"terrain.lod.levels", "int32"},     {"grass.density", "float"},        {"grass.mode", "enum"},
      {"grass.name", "string"}};
  ASSERT_EQ(params.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(params[i].path, expected[i].first);
    EXPECT_EQ(params[i].type_name(), expected[i].second) << params[i].path;
  }
  // Metadata travels with each descriptor.
  EXPECT_EQ(params[0].info.max, 64.0);
  EXPECT_TRUE(params[0].info.log_scale);
  EXPECT_EQ(params[1].info.rebuild, sylva::Rebuild::kOffline);
  EXPECT_STREQ(params[1].info.unit, "m");
  EXPECT_EQ(params[6].info.rebuild, sylva::Rebuild::kGpu);
  EXPECT_EQ(params[10].info.step, 0.1);
  EXPECT_STREQ(params[16].info.help, "Share of a LOD range used to morph");
  // Unbounded defaults.
  EXPECT_EQ(params[3].info.min, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(params[3].info.max, std::numeric_limits<double>::infinity());
  // Enum names are reachable for an editor's combo box.
  ASSERT_NE(params[19].ref.enum_table, nullptr);
  EXPECT_EQ(params[19].ref.enum_table->joined_names(), "blades, billboards, ground");
}

TEST(Params, DescriptorsPointIntoTheObject) {
  Scene s;
  const auto params = sylva::describe_params(s);
  EXPECT_EQ(params[0].ref.ptr, &s.terrain.max_pixel_error);
  EXPECT_EQ(&params[0].value<float>(), &s.terrain.max_pixel_error);
  params[0].value<float>() = 3.f;  // an editor widget writing directly
  EXPECT_EQ(s.terrain.max_pixel_error, 3.f);
  EXPECT_EQ(&params[11].value<glm::vec3>(), &s.terrain.sun_dir);
  EXPECT_EQ(&params[19].value<fixture::Grass::Mode>(), &s.grass.mode);
}

TEST(Params, PrefixIsPrepended) {
  Terrain t;
  const auto params = sylva::describe_params(t, "scene.terrain");
  EXPECT_EQ(params.front().path, "scene.terrain.max_pixel_error");
  EXPECT_EQ(params.back().path, "scene.terrain.lod.levels");
}

TEST(Params, GetStringOfEveryType) {
  Scene s;
  s.terrain.max_pixel_error = 0.1f;
  s.terrain.hash = std::numeric_limits<std::uint64_t>::max();
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"terrain.max_pixel_error", "0.1"},   {"terrain.world_scale", "2.5"},
      {"terrain.chunk_dim", "33"},          {"terrain.seed", "7"},
      {"terrain.offset", "-5"},             {"terrain.hash", "18446744073709551615"},
      {"terrain.skirts", "true"},           {"terrain.height_map", "maps/height.png"},
      {"terrain.criterion", "screen_space"}, {"terrain.quality", "low"},
      {"terrain.uv_scale", "1,1"},          {"terrain.sun_dir", "0,1,0"},
      {"terrain.tiles", "4,4"},             {"terrain.grid", "1,2,3"},
      {"terrain.lod.morph_fraction", "0.25"}, {"grass.mode", "blades"},
      {"grass.name", "meadow"}};
  for (const auto& [path, text] : expected) {
    auto got = sylva::get_param(s, path);
    ASSERT_TRUE(got.ok()) << got.error().message;
    EXPECT_EQ(*got, text) << path;
  }
}

TEST(Params, SetByPathEveryType) {
  Scene s;
  const auto set = [&](std::string_view path, std::string_view text) {
    sylva::Status st = sylva::set_param(s, path, text);
    EXPECT_TRUE(st.ok()) << path << "=" << text << ": " << (st.ok() ? "" : st.error().message);
  };
  set("terrain.max_pixel_error", "2");
  EXPECT_EQ(s.terrain.max_pixel_error, 2.f);
  set("terrain.max_pixel_error", " 0.5 ");
  EXPECT_EQ(s.terrain.max_pixel_error, 0.5f);
  set("terrain.max_pixel_error", "+3e0");
  EXPECT_EQ(s.terrain.max_pixel_error, 3.f);
  set("terrain.world_scale", "0.001");
  EXPECT_EQ(s.terrain.world_scale, 0.001);
  set("terrain.chunk_dim", "65");
  EXPECT_EQ(s.terrain.chunk_dim, 65);
  set("terrain.chunk_dim", "129.0");  // an integral number written as a float is exact
  EXPECT_EQ(s.terrain.chunk_dim, 129);
  set("terrain.seed", "4294967295");
  EXPECT_EQ(s.terrain.seed, 4294967295u);
  set("terrain.offset", "-999999999999");
  EXPECT_EQ(s.terrain.offset, -999999999999);
  set("terrain.hash", "18446744073709551615");
  EXPECT_EQ(s.terrain.hash, std::numeric_limits<std::uint64_t>::max());
  for (const char* f : {"false", "0", "off", "no"}) {
    s.terrain.skirts = true;
    set("terrain.skirts", f);
    EXPECT_FALSE(s.terrain.skirts) << f;
  }
  for (const char* t : {"true", "1", "on", "yes"}) {
    s.terrain.skirts = false;
    set("terrain.skirts", t);
    EXPECT_TRUE(s.terrain.skirts) << t;
  }
  set("terrain.height_map", "  a path with spaces.png");
  EXPECT_EQ(s.terrain.height_map, "  a path with spaces.png");  // strings are taken verbatim
  set("terrain.criterion", "distance");
  EXPECT_EQ(s.terrain.criterion, fixture::Criterion::kDistance);
  set("terrain.quality", "high");
  EXPECT_EQ(s.terrain.quality, fixture::Quality::kHigh);
  set("terrain.uv_scale", "2,3");
  EXPECT_EQ(s.terrain.uv_scale, glm::vec2(2.f, 3.f));
  set("terrain.sun_dir", "[0.5, -0.5, 0.25]");
  EXPECT_EQ(s.terrain.sun_dir, glm::vec3(0.5f, -0.5f, 0.25f));
  set("terrain.tint", "0.1 0.2 0.3 0.4");
  EXPECT_EQ(s.terrain.tint, glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
  set("terrain.tiles", "(8, 16)");
  EXPECT_EQ(s.terrain.tiles, glm::ivec2(8, 16));
  set("terrain.origin", "1e5,-2.5,100000.125");
  EXPECT_EQ(s.terrain.origin, glm::dvec3(1e5, -2.5, 100000.125));
  set("terrain.grid", "10,20,30");
  EXPECT_EQ(s.terrain.grid, glm::uvec3(10u, 20u, 30u));
  set("terrain.lod.levels", "12");
  EXPECT_EQ(s.terrain.lod.levels, 12);
  set("grass.mode", "ground");
  EXPECT_EQ(s.grass.mode, fixture::Grass::Mode::kGround);
}

TEST(Params, RangeErrorsNameThePathAndTheBound) {
  Scene s;
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "100"), "terrain.max_pixel_error: 100 is above the maximum 64");
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "0.01"),
            "terrain.max_pixel_error: 0.01 is below the minimum 0.05");
  EXPECT_EQ(set_error(s, "terrain.lod.morph_fraction", "1.5"), "terrain.lod.morph_fraction: 1.5 is above the maximum 1");
  EXPECT_EQ(set_error(s, "terrain.chunk_dim", "2"), "terrain.chunk_dim: 2 is below the minimum 3");
  EXPECT_EQ(set_error(s, "terrain.world_scale", "1e5"), "terrain.world_scale: 100000 is above the maximum 10000");
  EXPECT_EQ(set_error(s, "terrain.sun_dir", "0,2,0"), "terrain.sun_dir[1]: 2 is above the maximum 1");
  EXPECT_EQ(set_error(s, "terrain.tiles", "0,4"), "terrain.tiles[0]: 0 is below the minimum 1");
  EXPECT_EQ(set_error(s, "grass.name", ""), "grass.name: a string of length 0 is shorter than the minimum length 1");
  EXPECT_EQ(set_error(s, "grass.name", std::string(33, 'x')),
            "grass.name: a string of length 33 is longer than the maximum length 32");
  // Bounds are inclusive.
  EXPECT_TRUE(sylva::set_param(s, "terrain.max_pixel_error", "64").ok());
  EXPECT_TRUE(sylva::set_param(s, "terrain.max_pixel_error", "0.05").ok());
  EXPECT_TRUE(sylva::set_param(s, "terrain.chunk_dim", "1025").ok());
}

TEST(Params, TypeErrorsNameThePath) {
  Scene s;
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "abc"), "terrain.max_pixel_error: expected a number, got \"abc\"");
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", ""), "terrain.max_pixel_error: expected a number, got an empty string");
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "   "), "terrain.max_pixel_error: expected a number, got an empty string");
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "2px"), "terrain.max_pixel_error: expected a number, got \"2px\"");
  EXPECT_EQ(set_error(s, "terrain.chunk_dim", "2.5"), "terrain.chunk_dim: expected an integer, got 2.5");
  EXPECT_EQ(set_error(s, "terrain.skirts", "maybe"), "terrain.skirts: expected true or false, got \"maybe\"");
  EXPECT_EQ(set_error(s, "terrain.skirts", ""), "terrain.skirts: expected true or false, got an empty string");
  EXPECT_EQ(set_error(s, "terrain.sun_dir", "1,2"),
            "terrain.sun_dir: expected 3 numbers separated by commas, got 2 in \"1,2\"");
  EXPECT_EQ(set_error(s, "terrain.sun_dir", "0,x,0"), "terrain.sun_dir[1]: expected a number, got \"x\"");
  EXPECT_EQ(set_error(s, "terrain.sun_dir", "0,,0"), "terrain.sun_dir[1]: expected a number, got an empty string");
}

TEST(Params, NonFiniteAndHugeNumbersAreRejected) {
  Scene s;
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "nan"), "terrain.max_pixel_error: nan is not a finite number");
  EXPECT_EQ(set_error(s, "terrain.max_pixel_error", "inf"), "terrain.max_pixel_error: inf is not a finite number");
  EXPECT_EQ(set_error(s, "terrain.world_scale", "-inf"), "terrain.world_scale: -inf is not a finite number");
  EXPECT_EQ(set_error(s, "terrain.origin", "0,nan,0"), "terrain.origin[1]: nan is not a finite number");
  EXPECT_EQ(set_error(s, "terrain.world_scale", "1e400"), "terrain.world_scale: 1e400 is outside the range of a double");
  // A double that is no float: rejected, not turned into inf.
  EXPECT_EQ(set_error(s, "grass.density", "1e39"),
            "grass.density: 1e+39 is too large for a float (largest is 3.4028235e+38)");
  // Integers never wrap or truncate.
  EXPECT_EQ(set_error(s, "terrain.chunk_dim", "99999999999"),
            "terrain.chunk_dim: 99999999999 does not fit in int32 (-2147483648 to 2147483647)");
  EXPECT_EQ(set_error(s, "terrain.seed", "-1"), "terrain.seed: -1 does not fit in uint32 (0 to 4294967295)");
  EXPECT_EQ(set_error(s, "terrain.seed", "4294967296"), "terrain.seed: 4294967296 does not fit in uint32 (0 to 4294967295)");
  EXPECT_EQ(set_error(s, "terrain.hash", "18446744073709551616"),
            "terrain.hash: 18446744073709551616 does not fit in uint64 (0 to 18446744073709551615)");
  EXPECT_EQ(set_error(s, "terrain.offset", "-9223372036854775809"),
            "terrain.offset: -9223372036854775809 does not fit in int64 (-9223372036854775808 to 9223372036854775807)");
  // An integer in floating-point form beyond 2^53 has lost digits already: refused, not guessed.
  EXPECT_EQ(set_error(s, "terrain.hash", "1e18"),
            "terrain.hash: 1e+18 is not exact: an integer written as a floating-point number must be at most 2^53 "
            "in magnitude; write all its digits");
  EXPECT_TRUE(sylva::set_param(s, "terrain.hash", "1000000000000000000").ok());
  EXPECT_EQ(s.terrain.hash, 1000000000000000000u);
  EXPECT_TRUE(sylva::set_param(s, "terrain.hash", "9007199254740992.0").ok());
  EXPECT_EQ(s.terrain.hash, 9007199254740992u);
  EXPECT_EQ(set_error(s, "terrain.hash", "-1"), "terrain.hash: -1 does not fit in uint64 (0 to 18446744073709551615)");
  EXPECT_EQ(set_error(s, "terrain.offset", "1e13"), "terrain.offset: 10000000000000 is above the maximum 1000000000000");
}

TEST(Params, EnumErrorsListTheValidNames) {
  Scene s;
  EXPECT_EQ(set_error(s, "terrain.criterion", "screen"),
            "terrain.criterion: unknown value \"screen\"; valid values: screen_space, distance");
  EXPECT_EQ(set_error(s, "grass.mode", "1"), "grass.mode: unknown value \"1\"; valid values: blades, billboards, ground");
  EXPECT_EQ(set_error(s, "terrain.quality", ""), "terrain.quality: unknown value \"\"; valid values: low, high");
}

TEST(Params, UnknownPathsSuggestOrList) {
  Scene s;
  sylva::Status st = sylva::set_param(s, "terrain.max_pixl_error", "2");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, sylva::ErrorCode::kNotFound);
  EXPECT_EQ(st.error().message, "unknown parameter \"terrain.max_pixl_error\"; did you mean \"terrain.max_pixel_error\"?");

  st = sylva::set_param(s, "terrain.lod.zzzzzzzzzz", "2");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message,
            "unknown parameter \"terrain.lod.zzzzzzzzzz\"; known in terrain.lod: terrain.lod.morph_fraction, "
            "terrain.lod.levels");

  st = sylva::set_param(s, "voxelworld.size", "2");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "unknown parameter \"voxelworld.size\"; known names: terrain, grass");

  st = sylva::set_param(s, "terrain.lod", "2");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, sylva::ErrorCode::kInvalidArgument);
  EXPECT_EQ(st.error().message,
            "terrain.lod is a group of parameters, not a parameter; it holds terrain.lod.morph_fraction, "
            "terrain.lod.levels");

  st = sylva::set_param(s, "", "2");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, sylva::ErrorCode::kNotFound);
}

TEST(Params, GetOfUnknownPathIsAnError) {
  Scene s;
  auto got = sylva::get_param(s, "grass.densty");
  ASSERT_FALSE(got.ok());
  EXPECT_EQ(got.error().message, "unknown parameter \"grass.densty\"; did you mean \"grass.density\"?");
}

TEST(Params, ValidateReportsEveryViolationInOrder) {
  Scene s;
  EXPECT_TRUE(sylva::validate_params(s).ok());
  s.terrain.max_pixel_error = std::numeric_limits<float>::quiet_NaN();
  s.terrain.chunk_dim = 5000;
  s.terrain.sun_dir.z = std::numeric_limits<float>::infinity();
  s.terrain.quality = static_cast<fixture::Quality>(7);
  s.grass.name.clear();
  const auto violations = sylva::param_violations(sylva::describe_params(s));
  ASSERT_EQ(violations.size(), 5u);
  EXPECT_EQ(violations[0].message, "terrain.max_pixel_error: nan is not a finite number");
  EXPECT_EQ(violations[1].message, "terrain.chunk_dim: 5000 is above the maximum 1025");
  EXPECT_EQ(violations[2].message, "terrain.quality: value 7 has no name; valid values: low, high");
  EXPECT_EQ(violations[3].message, "terrain.sun_dir[2]: inf is not a finite number");
  EXPECT_EQ(violations[4].message, "grass.name: a string of length 0 is shorter than the minimum length 1");
  sylva::Status st = sylva::validate_params(s);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, sylva::ErrorCode::kInvalidArgument);
  EXPECT_EQ(std::count(st.error().message.begin(), st.error().message.end(), '\n'), 4);
  // An unnamed enum value still prints (as its number) so messages and files can show it.
  EXPECT_EQ(*sylva::get_param(s, "terrain.quality"), "7");
}

TEST(Params, TypedDescriptorSetValidates) {
  Scene s;
  auto d = sylva::find_param(sylva::describe_params(s), "terrain.max_pixel_error");
  ASSERT_TRUE(d.ok());
  EXPECT_TRUE(d->set(4.f).ok());
  EXPECT_EQ(s.terrain.max_pixel_error, 4.f);
  sylva::Status st = d->set(128.f);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "terrain.max_pixel_error: 128 is above the maximum 64");
  EXPECT_EQ(s.terrain.max_pixel_error, 4.f);
  auto mode = sylva::find_param(sylva::describe_params(s), "grass.mode");
  ASSERT_TRUE(mode.ok());
  EXPECT_TRUE(mode->set(fixture::Grass::Mode::kBillboards).ok());
  EXPECT_EQ(s.grass.mode, fixture::Grass::Mode::kBillboards);
  EXPECT_FALSE(mode->set(static_cast<fixture::Grass::Mode>(99)).ok());
  EXPECT_EQ(s.grass.mode, fixture::Grass::Mode::kBillboards);
  auto sun = sylva::find_param(sylva::describe_params(s), "terrain.sun_dir");
  EXPECT_TRUE(sun->set(glm::vec3(0.f, 0.f, 1.f)).ok());
  EXPECT_EQ(s.terrain.sun_dir, glm::vec3(0.f, 0.f, 1.f));
  EXPECT_FALSE(sun->set(glm::vec3(0.f, 0.f, 1.5f)).ok());
  EXPECT_EQ(s.terrain.sun_dir, glm::vec3(0.f, 0.f, 1.f));
}

TEST(ParamsDeathTest, TypedAccessWithTheWrongTypeAsserts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Scene s;
  const auto params = sylva::describe_params(s);
  EXPECT_DEATH((void)params[0].value<double>(), "terrain.max_pixel_error is a float");
}

struct Dup {
  int a = 0, b = 0;
  template <class V> void visit(V& v) { v(a, "x"); v(b, "x"); }
};
struct Dotted {
  int a = 0;
  template <class V> void visit(V& v) { v(a, "a.b"); }
};

TEST(ParamsDeathTest, DuplicateNamesAssert) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Dup d;
  EXPECT_DEATH((void)sylva::describe_params(d), "listed twice");
}

TEST(ParamsDeathTest, NamesWithDotsAssert) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Dotted d;
  EXPECT_DEATH((void)sylva::describe_params(d), "contains '.'");
}

TEST(Params, DiffSaysWhatToRebuild) {
  Scene a;
  Scene b = a;
  EXPECT_TRUE(sylva::diff_params(a, b).empty());
  EXPECT_EQ(sylva::max_rebuild(sylva::diff_params(a, b)), sylva::Rebuild::kNone);
  b.terrain.max_pixel_error = 2.f;
  auto changes = sylva::diff_params(a, b);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].path, "terrain.max_pixel_error");
  EXPECT_EQ(sylva::max_rebuild(changes), sylva::Rebuild::kNone);
  b.terrain.skirts = false;
  EXPECT_EQ(sylva::max_rebuild(sylva::diff_params(a, b)), sylva::Rebuild::kGpu);
  b.terrain.world_scale = 3.0;
  b.grass.name = "lawn";
  changes = sylva::diff_params(a, b);
  ASSERT_EQ(changes.size(), 4u);
  EXPECT_EQ(changes[3].path, "grass.name");
  EXPECT_EQ(sylva::max_rebuild(changes), sylva::Rebuild::kOffline);
  EXPECT_STREQ(sylva::to_string(sylva::Rebuild::kOffline), "offline");
}

TEST(Params, ParseAssignment) {
  auto kv = sylva::parse_param_assignment("terrain.max_pixel_error=2");
  ASSERT_TRUE(kv.ok());
  EXPECT_EQ(kv->first, "terrain.max_pixel_error");
  EXPECT_EQ(kv->second, "2");
  kv = sylva::parse_param_assignment("grass.name=a=b");  // the value may contain '='
  ASSERT_TRUE(kv.ok());
  EXPECT_EQ(kv->second, "a=b");
  kv = sylva::parse_param_assignment("terrain.max_pixel_error");
  ASSERT_FALSE(kv.ok());
  EXPECT_EQ(kv.error().message,
            "expected path=value (for example terrain.max_pixel_error=2), got \"terrain.max_pixel_error\"");
  EXPECT_FALSE(sylva::parse_param_assignment("=2").ok());
}

TEST(ParamRegistry, SectionsComposedAtRunTime) {
  Terrain terrain;
  fixture::Grass grass;
  grass.name = "g";
  sylva::ParamRegistry registry;
  registry.add("terrain", terrain);
  registry.add("grass", grass);
  EXPECT_TRUE(registry.contains("terrain"));
  EXPECT_EQ(registry.section_names(), (std::vector<std::string>{"terrain", "grass"}));
  const auto params = registry.describe();
  EXPECT_EQ(params.size(), 21u);
  EXPECT_EQ(params.front().path, "terrain.max_pixel_error");
  EXPECT_EQ(params.back().path, "grass.name");

  ASSERT_TRUE(registry.set_assignment("terrain.max_pixel_error=2").ok());
  EXPECT_EQ(terrain.max_pixel_error, 2.f);
  ASSERT_TRUE(registry.set("grass.mode", "billboards").ok());
  EXPECT_EQ(grass.mode, fixture::Grass::Mode::kBillboards);
  EXPECT_EQ(*registry.get("terrain.lod.levels"), "8");
  EXPECT_EQ(registry.find("terrain.skirts")->info.rebuild, sylva::Rebuild::kGpu);

  sylva::Status st = registry.set_assignment("terrain.max_pixel_error=100");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "terrain.max_pixel_error: 100 is above the maximum 64");
  EXPECT_EQ(terrain.max_pixel_error, 2.f);
  st = registry.set_assignment("voxel.size=3");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "unknown parameter \"voxel.size\"; known names: terrain, grass");

  EXPECT_TRUE(registry.validate().ok());
  grass.name.clear();
  EXPECT_FALSE(registry.validate().ok());

  EXPECT_TRUE(registry.remove("grass"));
  EXPECT_FALSE(registry.remove("grass"));
  EXPECT_FALSE(registry.set("grass.mode", "ground").ok());
  EXPECT_EQ(registry.describe().size(), 18u);
}

TEST(ParamRegistry, TypeErasedSection) {
  // A section given as a bare visit function (for example a module that assembles its
  // settings from several structs).
  float a = 1.f;
  int b = 2;
  sylva::ParamRegistry registry;
  registry.add_section("custom", [&](sylva::ParamCollector& v) {
    v(a, "a", {.min = 0.f});
    v(b, "b");
  });
  ASSERT_TRUE(registry.set("custom.a", "5").ok());
  ASSERT_TRUE(registry.set("custom.b", "-3").ok());
  EXPECT_EQ(a, 5.f);
  EXPECT_EQ(b, -3);
  EXPECT_FALSE(registry.set("custom.a", "-1").ok());
}

TEST(ParamRegistryDeathTest, DuplicateSectionAsserts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  Terrain t;
  sylva::ParamRegistry registry;
  registry.add("terrain", t);
  EXPECT_DEATH(registry.add("terrain", t), "registered twice");
}

}  // namespace
