// JSON load/save of settings driven by visit(): lossless round trip of every supported type,
// errors naming the full JSON path at every level, unknown keys as warnings, missing keys keep
// their defaults, nothing written on error.

#include "params_fixtures.hpp"

#include <sylva/core/params_json.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace {

using fixture::Scene;
using fixture::Terrain;
using json = nlohmann::json;

Scene non_default_scene() {
  Scene s;
  s.terrain.max_pixel_error = 0.1f;
  s.terrain.world_scale = 1.0 / 3.0;
  s.terrain.chunk_dim = 1025;
  s.terrain.seed = 4294967295u;
  s.terrain.offset = -999999999999;
  s.terrain.hash = std::numeric_limits<std::uint64_t>::max();
  s.terrain.skirts = false;
  s.terrain.height_map = "unicode \xc3\xa9\xe2\x82\xac \"quoted\" \\ slash\nnewline";
  s.terrain.criterion = fixture::Criterion::kDistance;
  s.terrain.quality = fixture::Quality::kHigh;
  s.terrain.uv_scale = {0.3f, 99.99f};
  s.terrain.sun_dir = {-0.577350269f, 0.577350269f, 1e-30f};
  s.terrain.tint = {0.f, 0.25f, 1.f / 3.f, 1.f};
  s.terrain.tiles = {1, 64};
  s.terrain.origin = {1e5 + 0.123456789, -6.02e23, 1e-300};
  s.terrain.grid = {0u, 1000u, 999u};
  s.terrain.lod.morph_fraction = 0.7f;
  s.terrain.lod.levels = 24;
  s.grass.density = 12345.678f;
  s.grass.mode = fixture::Grass::Mode::kGround;
  s.grass.name = "x";
  return s;
}

std::string load_error(Scene& s, const json& j, std::vector<std::string>* warnings_out = nullptr) {
  std::vector<std::string> warnings;
  const Scene before = s;
  sylva::Status st = sylva::params_from_json(s, j, warnings);
  EXPECT_FALSE(st.ok()) << j.dump() << " was accepted";
  EXPECT_EQ(s, before) << "a failed load modified the settings";
  if (warnings_out != nullptr) *warnings_out = warnings;
  return st.ok() ? std::string() : st.error().message;
}

TEST(ParamsJson, SavesNestedObjectsWithReadableValues) {
  Scene s;
  s.terrain.max_pixel_error = 0.1f;
  const json j = sylva::params_to_json(s);
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["terrain"]["max_pixel_error"].get<double>(), 0.1);  // shortest float text, not 0.100000001
  EXPECT_EQ(j["terrain"]["max_pixel_error"].dump(), "0.1");
  EXPECT_EQ(j["terrain"]["world_scale"], 2.5);
  EXPECT_EQ(j["terrain"]["chunk_dim"], 33);
  EXPECT_EQ(j["terrain"]["skirts"], true);
  EXPECT_EQ(j["terrain"]["height_map"], "maps/height.png");
  EXPECT_EQ(j["terrain"]["criterion"], "screen_space");
  EXPECT_EQ(j["terrain"]["quality"], "low");
  EXPECT_EQ(j["terrain"]["sun_dir"], json::parse("[0.0, 1.0, 0.0]"));
  EXPECT_EQ(j["terrain"]["tiles"], json::parse("[4, 4]"));
  EXPECT_EQ(j["terrain"]["lod"]["levels"], 8);
  EXPECT_EQ(j["grass"]["mode"], "blades");
  EXPECT_EQ(j["grass"]["name"], "meadow");
  EXPECT_EQ(j.size(), 2u);
  EXPECT_EQ(j["terrain"].size(), 17u);
}

TEST(ParamsJson, RoundTripIsLosslessForEveryType) {
  const Scene original = non_default_scene();
  ASSERT_TRUE(sylva::validate_params(original).ok()) << sylva::validate_params(original).error().message;
  // Through text, as a scene file would be.
  const std::string text = sylva::params_to_json(original).dump(2);
  auto parsed = sylva::parse_json_text(text, "scene.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error().message;
  Scene loaded;
  std::vector<std::string> warnings;
  sylva::Status st = sylva::params_from_json(loaded, *parsed, warnings);
  ASSERT_TRUE(st.ok()) << st.error().message;
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(loaded, original);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(loaded.terrain.sun_dir.z), std::bit_cast<std::uint32_t>(original.terrain.sun_dir.z));
  EXPECT_EQ(sylva::params_to_json(loaded).dump(2), text);
}

TEST(ParamsJson, MissingKeysKeepTheirValues) {
  Scene s;
  s.terrain.chunk_dim = 65;
  std::vector<std::string> warnings;
  ASSERT_TRUE(sylva::params_from_json(s, json::parse(R"({"terrain": {"max_pixel_error": 3}})"), warnings).ok());
  EXPECT_EQ(s.terrain.max_pixel_error, 3.f);
  EXPECT_EQ(s.terrain.chunk_dim, 65);
  EXPECT_EQ(s.grass, fixture::Grass{.name = "meadow"});
  ASSERT_TRUE(sylva::params_from_json(s, json::object(), warnings).ok());
  EXPECT_EQ(s.terrain.max_pixel_error, 3.f);
  EXPECT_TRUE(warnings.empty());
}

TEST(ParamsJson, UnknownKeysAreWarningsNotDropped) {
  Scene s;
  std::vector<std::string> warnings;
  const json j = json::parse(R"({
    "terrain": {"max_pixl_error": 3, "chunk_dim": 65, "lod": {"levls": 3, "extra": {"a": 1}}},
    "voxel": {"size": 3},
    "grass": {"dots.in.key": 1}
  })");
  ASSERT_TRUE(sylva::params_from_json(s, j, warnings).ok());
  EXPECT_EQ(s.terrain.chunk_dim, 65);  // the known keys still load
  ASSERT_EQ(warnings.size(), 5u);
  // nlohmann's objects iterate keys in sorted order.
  EXPECT_EQ(warnings[0], "grass.dots.in.key: unknown key (a value), ignored");
  EXPECT_EQ(warnings[1], "terrain.lod.extra: unknown key (an object), ignored");
  EXPECT_EQ(warnings[2], "terrain.lod.levls: unknown key (a value), ignored; did you mean \"levels\"?");
  EXPECT_EQ(warnings[3], "terrain.max_pixl_error: unknown key (a value), ignored; did you mean \"max_pixel_error\"?");
  EXPECT_EQ(warnings[4], "voxel: unknown key (an object), ignored");
}

TEST(ParamsJson, WrongTypesAtEveryLevelNameThePath) {
  Scene s;
  EXPECT_EQ(load_error(s, json::parse("5")), "(top level): expected an object, got number 5");
  EXPECT_EQ(load_error(s, json::parse("[1]")), "(top level): expected an object, got array [1]");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": 5})")), "terrain: expected an object, got number 5");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"lod": "deep"}})")),
            "terrain.lod: expected an object, got string \"deep\"");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"max_pixel_error": "abc"}})")),
            "terrain.max_pixel_error: expected a number, got string \"abc\"");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"max_pixel_error": null}})")),
            "terrain.max_pixel_error: expected a number, got null");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"max_pixel_error": [1]}})")),
            "terrain.max_pixel_error: expected a number, got array [1]");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"chunk_dim": "33"}})")),
            "terrain.chunk_dim: expected an integer, got string \"33\"");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"skirts": 1}})")),
            "terrain.skirts: expected true or false, got number 1");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"height_map": 5}})")),
            "terrain.height_map: expected a string, got number 5");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"criterion": 1}})")),
            "terrain.criterion: expected one of screen_space, distance (a string), got number 1");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"criterion": "fast"}})")),
            "terrain.criterion: unknown value \"fast\"; valid values: screen_space, distance");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"sun_dir": [0, 1]}})")),
            "terrain.sun_dir: expected an array of 3 numbers, got array [0,1]");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"sun_dir": {"x": 0}}})")),
            "terrain.sun_dir: expected an array of 3 numbers, got object {\"x\":0}");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"sun_dir": [0, "1", 0]}})")),
            "terrain.sun_dir[1]: expected a number, got string \"1\"");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"tiles": [1, 2.5]}})")),
            "terrain.tiles[1]: expected an integer, got 2.5");
  EXPECT_EQ(load_error(s, json::parse(R"({"grass": {"mode": null}})")),
            "grass.mode: expected one of blades, billboards, ground (a string), got null");
}

TEST(ParamsJson, RangeAndNumberErrors) {
  Scene s;
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"max_pixel_error": 100}})")),
            "terrain.max_pixel_error: 100 is above the maximum 64");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"chunk_dim": 99999999999}})")),
            "terrain.chunk_dim: 99999999999 does not fit in int32 (-2147483648 to 2147483647)");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"seed": -1}})")),
            "terrain.seed: -1 does not fit in uint32 (0 to 4294967295)");
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"hash": 1e30}})")),
            "terrain.hash: 1e+30 does not fit in uint64 (0 to 18446744073709551615)");
  EXPECT_EQ(load_error(s, json::parse(R"({"grass": {"density": 1e39}})")),
            "grass.density: 1e+39 is too large for a float (largest is 3.4028235e+38)");
  EXPECT_EQ(load_error(s, json::parse(R"({"grass": {"name": ""}})")),
            "grass.name: a string of length 0 is shorter than the minimum length 1");
  // nlohmann reads -9223372036854775809 as the double -2^63: the lost digit must not become INT64_MIN.
  EXPECT_EQ(load_error(s, json::parse(R"({"terrain": {"offset": -9223372036854775809}})")),
            "terrain.offset: -9.223372036854776e+18 is not exact: an integer written as a floating-point number "
            "must be at most 2^53 in magnitude; write all its digits");
  // NaN and Inf cannot be written in JSON text but can be put into a json value by code.
  json j;
  j["terrain"]["world_scale"] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(load_error(s, j), "terrain.world_scale: nan is not a finite number");
  j["terrain"]["world_scale"] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(load_error(s, j), "terrain.world_scale: inf is not a finite number");
  j = json();
  j["terrain"]["origin"] = json::array({0.0, -std::numeric_limits<double>::infinity(), 0.0});
  EXPECT_EQ(load_error(s, j), "terrain.origin[1]: -inf is not a finite number");
  // An integral float is an exact integer.
  std::vector<std::string> warnings;
  ASSERT_TRUE(sylva::params_from_json(s, json::parse(R"({"terrain": {"chunk_dim": 65.0, "seed": 4294967295}})"), warnings).ok());
  EXPECT_EQ(s.terrain.chunk_dim, 65);
  EXPECT_EQ(s.terrain.seed, 4294967295u);
}

TEST(ParamsJson, NumbersJsonCannotHoldAreParseErrors) {
  auto r = sylva::parse_json_text(R"({"terrain": {"world_scale": 1e400}})", "scene.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, sylva::ErrorCode::kParse);
  EXPECT_EQ(r.error().message, "scene.json: number overflow parsing '1e400'");
  // Integers too large for 64 bits parse as doubles, and then do not fit an int.
  r = sylva::parse_json_text(R"({"terrain": {"chunk_dim": 99999999999999999999999}})");
  ASSERT_TRUE(r.ok());
  Scene s;
  EXPECT_EQ(load_error(s, *r), "terrain.chunk_dim: 1e+23 does not fit in int32 (-2147483648 to 2147483647)");
}

TEST(ParamsJson, ParseErrorsGiveLineAndColumn) {
  auto r = sylva::parse_json_text("{\n  \"terrain\": {\n    \"chunk_dim\": 3x\n  }\n}", "scene.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, sylva::ErrorCode::kParse);
  EXPECT_TRUE(r.error().message.starts_with("scene.json:3:")) << r.error().message;
  EXPECT_NE(r.error().message.find("syntax error"), std::string::npos) << r.error().message;
  r = sylva::parse_json_text("", "empty.json");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.error().message.starts_with("empty.json:1:1:")) << r.error().message;
}

TEST(ParamsJson, AllErrorsReportedTogetherAndNothingWritten) {
  Scene s;
  const std::string message = load_error(s, json::parse(R"({
    "terrain": {"max_pixel_error": 2, "chunk_dim": "x", "lod": {"morph_fraction": 3}},
    "grass": {"mode": "none"}
  })"));
  EXPECT_EQ(message,
            "grass.mode: unknown value \"none\"; valid values: blades, billboards, ground\n"
            "terrain.chunk_dim: expected an integer, got string \"x\"\n"
            "terrain.lod.morph_fraction: 3 is above the maximum 1");
  EXPECT_EQ(s.terrain.max_pixel_error, 1.f);  // the valid value was not applied either
}

TEST(ParamsJson, PrefixNamesTheSectionInMessages) {
  Terrain t;
  std::vector<std::string> warnings;
  sylva::Status st = sylva::params_from_json(t, json::parse(R"({"lod": {"levels": 0}, "typo": 1})"), warnings, "terrain");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "terrain.lod.levels: 0 is below the minimum 1");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "terrain.typo: unknown key (a value), ignored");
  st = sylva::params_from_json(t, json::parse("true"), warnings, "terrain");
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "terrain: expected an object, got boolean true");
}

TEST(ParamsJson, SingleParameter) {
  Scene s;
  const auto params = sylva::describe_params(s);
  auto d = sylva::find_param(params, "terrain.tint");
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(sylva::param_to_json(*d), json::parse("[1.0, 1.0, 1.0, 1.0]"));
  ASSERT_TRUE(sylva::param_from_json(*d, json::parse("[0.5, 0.5, 0.5, 1]")).ok());
  EXPECT_EQ(s.terrain.tint, glm::vec4(0.5f, 0.5f, 0.5f, 1.f));
  sylva::Status st = sylva::param_from_json(*d, json::parse("[0.5, 0.5, 0.5, 2]"));
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().message, "terrain.tint[3]: 2 is above the maximum 1");
  EXPECT_EQ(s.terrain.tint, glm::vec4(0.5f, 0.5f, 0.5f, 1.f));
}

TEST(ParamsJson, RegistryRoundTripAndUnknownSections) {
  Terrain terrain;
  fixture::Grass grass{.name = "g"};
  sylva::ParamRegistry registry;
  registry.add("terrain", terrain);
  registry.add("grass", grass);
  terrain.max_pixel_error = 4.f;
  grass.mode = fixture::Grass::Mode::kBillboards;
  const json saved = sylva::params_to_json(registry);
  EXPECT_EQ(saved["terrain"]["max_pixel_error"], 4.0);
  EXPECT_EQ(saved["grass"]["mode"], "billboards");

  terrain = Terrain{};
  grass = fixture::Grass{.name = "g"};
  json with_extra = saved;
  with_extra["voxel"] = json::object();
  std::vector<std::string> warnings;
  ASSERT_TRUE(sylva::params_from_json(registry, with_extra, warnings).ok());
  EXPECT_EQ(terrain.max_pixel_error, 4.f);
  EXPECT_EQ(grass.mode, fixture::Grass::Mode::kBillboards);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "voxel: unknown key (an object), ignored");

  sylva::ParamRegistry empty_section;
  empty_section.add_section("lighting", [](sylva::ParamCollector&) {});
  EXPECT_EQ(sylva::params_to_json(empty_section), json::parse(R"({"lighting": {}})"));
}

TEST(ParamsJson, SchemaDescribesEveryParameter) {
  Scene s;
  const json schema = sylva::params_schema_json(sylva::describe_params(s));
  ASSERT_TRUE(schema.is_array());
  ASSERT_EQ(schema.size(), 21u);
  const json& mpe = schema[0];
  EXPECT_EQ(mpe["path"], "terrain.max_pixel_error");
  EXPECT_EQ(mpe["type"], "float");
  EXPECT_EQ(mpe["value"], 1.0);
  EXPECT_EQ(mpe["max"], 64.0);
  EXPECT_EQ(mpe["unit"], "px");
  EXPECT_EQ(mpe["rebuild"], "none");
  EXPECT_EQ(mpe["log_scale"], true);
  EXPECT_FALSE(schema[3].contains("min"));  // seed: unbounded
  EXPECT_EQ(schema[1]["rebuild"], "offline");
  EXPECT_EQ(schema[19]["values"], json::parse(R"(["blades", "billboards", "ground"])"));
  EXPECT_EQ(schema[10]["step"], 0.1);
}

}  // namespace

// A 70,000-deep file (140 KB) overflowed the stack; the bound refuses it before parsing, naming
// where the nesting goes too deep. Brackets inside strings do not nest.
TEST(ParamsJson, NestingDeeperThanTheBoundIsAClearError) {
  const std::string deep = std::string(70000, '[') + std::string(70000, ']');
  auto r = sylva::parse_json_text(deep, "deep.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, sylva::ErrorCode::kLimit);
  EXPECT_EQ(r.error().message, "deep.json:1:129: nested deeper than 128 levels");
  const std::string objects = "{\"a\":\n" + std::string(200, '{') + std::string(200, '}') + "}";
  auto o = sylva::parse_json_text(objects, "o.json");
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.error().message, "o.json:2:128: nested deeper than 128 levels");
  const std::string at_bound = std::string(sylva::kMaxJsonDepth, '[') + std::string(sylva::kMaxJsonDepth, ']');
  EXPECT_TRUE(sylva::parse_json_text(at_bound, "ok.json").ok());
  const std::string in_string = "{\"name\": \"" + std::string(1000, '[') + "\\\"{{{\"}";
  auto s = sylva::parse_json_text(in_string, "s.json");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ((*s)["name"].get<std::string>().size(), 1004u);
}
