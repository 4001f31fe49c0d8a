// Scene files: lossless round trip, unknown keys kept and reported, errors naming the JSON path,
// built-out modules named, parameters addressable by path.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene_document.hpp>

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <map>
#include <unistd.h>

namespace fs = std::filesystem;
using sylva::scene::SceneDocument;

namespace {

const char* kFullScene = R"({
  "sylva_scene": 1,
  "name": "Round trip",
  "camera": {"position": [1.5, 2.25, -3.0], "yaw_deg": 0.1, "pitch_deg": -7.3, "fov_deg": 55, "height_mode": "above_ground"},
  "sun": {"azimuth_deg": 123.456, "elevation_deg": 33.3, "follow_clock": true, "color": [1, 0.9, 0.8]},
  "wind": {"strength": 7.7, "direction_deg": 271.1, "seed": 4294967295},
  "environment": {"time_of_day_h": 17.25, "season": 0.61, "latitude_deg": -33.9},
  "bookmarks": {"a": {"position": [1e6, 2, 3], "yaw_deg": 170}, "b": {"position": [0.1, 0.2, 0.3]}},
  "camera_paths": {"fly": {"interpolation": "linear", "loop": true,
                            "keys": [{"time_s": 0, "position": [0, 1, 0]}, {"time_s": 2.5, "position": [10, 1, 0], "yaw_deg": 90},
                                     {"time_s": 5, "position": [0, 1, 0], "future_key": {"x": 1}}]}},
  "ground": {"resolution": 65, "size": 512.5, "noise": {"octaves": 3, "frequency": 0.003},
             "maps": {"height": "maps/h.exr", "mystery": "maps/m.png"}, "ground_colour": "green"},
  "plugins": [1, 2, {"three": 3}]
})";

std::string text_of(const SceneDocument& d) { return d.to_text(); }

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_scene_doc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(SceneDocument, RoundTripIsLosslessAndKeepsUnknownKeys) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(kFullScene, "full.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_EQ(doc->name, "Round trip");
  EXPECT_EQ(doc->camera.position, glm::dvec3(1.5, 2.25, -3.0));
  EXPECT_EQ(doc->wind.seed, 4294967295u);
  EXPECT_FLOAT_EQ(doc->environment.latitude_deg, -33.9f);
  ASSERT_EQ(doc->camera_paths.at("fly").keys.size(), 3u);
  EXPECT_TRUE(doc->camera_paths.at("fly").settings.loop);
  ASSERT_TRUE(doc->has_module("ground"));
  EXPECT_EQ(doc->module("ground")->maps.at("height"), "maps/h.exr");

  // Every unknown key is reported with its JSON path.
  const std::vector<std::string> expected = {"plugins", "ground.ground_colour", "ground.maps.mystery",
                                             "camera_paths.fly.keys[2].future_key"};
  for (const std::string& path : expected) {
    const bool found = std::any_of(warnings.begin(), warnings.end(),
                                   [&](const std::string& w) { return w.find(path + ": unknown key") != std::string::npos; });
    EXPECT_TRUE(found) << "no warning for " << path;
  }
  EXPECT_EQ(warnings.size(), expected.size());
  for (const std::string& w : warnings) EXPECT_NE(w.find("full.json"), std::string::npos) << w;

  // Saved text holds the unknown keys unchanged...
  const nlohmann::json saved = doc->to_json();
  EXPECT_EQ(saved["plugins"], nlohmann::json::parse(R"([1, 2, {"three": 3}])"));
  EXPECT_EQ(saved["ground"]["ground_colour"], "green");
  EXPECT_EQ(saved["ground"]["maps"]["mystery"], "maps/m.png");
  EXPECT_EQ(saved["camera_paths"]["fly"]["keys"][2]["future_key"]["x"], 1);
  // ...and loading it again gives exactly the same document (floats bit-exact).
  std::vector<std::string> warnings2;
  auto again = SceneDocument::from_text(text_of(*doc), "again.json", warnings2);
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(text_of(*again), text_of(*doc));
  EXPECT_EQ(again->sun.azimuth_deg, 123.456f);
  EXPECT_EQ(again->camera.yaw_deg, 0.1f);
  EXPECT_EQ(again->bookmarks.at("a").position, glm::dvec3(1e6, 2, 3));
  EXPECT_EQ(warnings2.size(), warnings.size());
}

TEST(SceneDocument, SaveAndLoadThroughAFileResolvesMapPaths) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(kFullScene, "full.json", warnings);
  ASSERT_TRUE(doc.ok());
  const fs::path file = temp_dir() / "sub" / "scene.json";
  fs::create_directories(file.parent_path());
  ASSERT_TRUE(doc->save(file).ok());
  auto loaded = SceneDocument::load(file, warnings);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->directory(), file.parent_path());
  EXPECT_EQ(loaded->resolve("maps/h.exr"), file.parent_path() / "maps/h.exr");
  EXPECT_EQ(loaded->resolve("/abs/x.png"), fs::path("/abs/x.png"));
  EXPECT_EQ(text_of(*loaded), text_of(*doc));
}

TEST(SceneDocument, RemovedSectionTakesItsUnknownKeysWithIt) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(kFullScene, "full.json", warnings);
  ASSERT_TRUE(doc.ok());
  ASSERT_TRUE(doc->remove_module("ground"));
  const nlohmann::json saved = doc->to_json();
  EXPECT_FALSE(saved.contains("ground")) << saved.dump();
  EXPECT_TRUE(saved.contains("plugins"));
  doc->camera_paths.clear();
  EXPECT_FALSE(doc->to_json().contains("camera_paths"));
}

TEST(SceneDocument, MalformedScenesNameTheJsonPath) {
  struct Case {
    const char* text;
    const char* path;
  };
  std::vector<Case> cases = {
      {R"({"camera": {"fov_deg": 500}})", "camera.fov_deg"},
      {R"({"camera": [1, 2]})", "camera: expected an object"},
      {R"({"sun": {"elevation_deg": "high"}})", "sun.elevation_deg"},
      {R"({"wind": {"strength": -1}})", "wind.strength"},
      {R"({"environment": {"season": 2}})", "environment.season"},
      {R"({"ground": {"noise": {"octaves": "many"}}})", "ground.noise.octaves"},
      {R"({"ground": {"resolution": 1}})", "ground.resolution"},
      {R"({"ground": {"maps": {"height": 3}}})", "ground.maps.height"},
      {R"({"ground": {"maps": []}})", "ground.maps"},
      {R"({"ground": 5})", "ground: expected an object"},
      {R"({"bookmarks": {"a": {"pitch_deg": 100}}})", "bookmarks.a.pitch_deg"},
      {R"({"bookmarks": []})", "bookmarks"},
      {R"({"camera_paths": {"fly": {"keys": [{"time_s": 1}, {"time_s": 0.5}]}}})", "camera_paths.fly.keys[1].time_s"},
      {R"({"camera_paths": {"fly": {"keys": []}}})", "camera_paths.fly.keys"},
      {R"({"camera_paths": {"fly": {}}})", "camera_paths.fly.keys"},
      {R"({"camera_paths": {"fly": {"keys": [{"position": [0, "x", 0]}]}}})", "camera_paths.fly.keys[0].position"},
      {R"({"camera_paths": {"fly": {"keys": [{"time_s": 0}, {"time_s": 1, "height_mode": "above_ground"}]}}})",
       "camera_paths.fly.keys[1].height_mode"},
      {R"({"camera_paths": {"fly": {"interpolation": "bezier", "keys": [{"time_s": 0}]}}})",
       "camera_paths.fly.interpolation"},
      {R"({"sylva_scene": 99})", "sylva_scene: version 99 is newer"},
      {R"({"sylva_scene": "one"})", "sylva_scene"},
      {R"({"name": 3})", "name"},
  };
  if (sylva::scene::find_module("grass")) {
    cases.push_back({R"({"grass": {"blade": {"height_min": 0.9, "height_max": 0.3}}})", "grass.blade.height_min"});
    cases.push_back({R"({"grass": {"area_min": [10, 10], "area_max": [0, 20]}})", "grass.area_max"});
    cases.push_back({R"({"grass": {"field": {"density": -5}}})", "grass.field.density"});
  }
  if (sylva::scene::find_module("terrain")) {
    cases.push_back({R"({"ground": {}, "terrain": {}})", "one ground"});
  }
  for (const Case& c : cases) {
    std::vector<std::string> warnings;
    auto doc = SceneDocument::from_text(c.text, "bad.json", warnings);
    ASSERT_FALSE(doc.ok()) << c.text;
    EXPECT_NE(doc.error().message.find(c.path), std::string::npos) << "text: " << c.text << "\nmessage: " << doc.error().message;
    EXPECT_NE(doc.error().message.find("bad.json"), std::string::npos) << doc.error().message;
  }
  // Several problems are reported together.
  std::vector<std::string> warnings;
  auto both = SceneDocument::from_text(R"({"camera": {"fov_deg": 500}, "sun": {"intensity": -1}})", "two.json", warnings);
  ASSERT_FALSE(both.ok());
  EXPECT_NE(both.error().message.find("camera.fov_deg"), std::string::npos);
  EXPECT_NE(both.error().message.find("sun.intensity"), std::string::npos);
  // Malformed JSON names file:line:column.
  auto broken = SceneDocument::from_text("{\n  \"camera\": ", "broken.json", warnings);
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("broken.json:2"), std::string::npos) << broken.error().message;
  auto missing = SceneDocument::load("/nonexistent/scene.json", warnings);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/scene.json"), std::string::npos);
}

TEST(SceneDocument, TyposGetADidYouMean) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"sun": {"elevaton_deg": 45}, "bookmarsk": {}})", "typo.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("did you mean \"bookmarks\""), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("sun.elevaton_deg"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("elevation_deg"), std::string::npos) << warnings[1];
}

TEST(SceneDocument, ModulesThatAreBuiltOutAreNamed) {
  // The registry matches the build configuration.
  EXPECT_NE(sylva::scene::find_module("ground"), nullptr);
#ifdef SYLVA_HAS_GRASS
  EXPECT_NE(sylva::scene::find_module("grass"), nullptr);
#else
  EXPECT_EQ(sylva::scene::find_module("grass"), nullptr);
#endif
#ifdef SYLVA_HAS_VOXEL
  EXPECT_NE(sylva::scene::find_module("voxel"), nullptr);
#else
  EXPECT_EQ(sylva::scene::find_module("voxel"), nullptr);
#endif
#ifdef SYLVA_HAS_TERRAIN
  EXPECT_NE(sylva::scene::find_module("terrain"), nullptr);
#else
  EXPECT_EQ(sylva::scene::find_module("terrain"), nullptr);
#endif
#ifdef SYLVA_HAS_VEGETATION
  EXPECT_NE(sylva::scene::find_module("vegetation"), nullptr);
#else
  EXPECT_EQ(sylva::scene::find_module("vegetation"), nullptr);
#endif
  for (std::string_view name : sylva::scene::known_modules()) {
    std::vector<std::string> warnings;
    const std::string text = "{\"" + std::string(name) + "\": {}}";
    auto doc = SceneDocument::from_text(text, "m.json", warnings);
    if (sylva::scene::find_module(name)) {
      EXPECT_TRUE(doc.ok()) << name << ": " << doc.error().message;
    } else {
      ASSERT_FALSE(doc.ok()) << name;
      EXPECT_NE(doc.error().message.find("built without the " + std::string(name) + " module"), std::string::npos)
          << doc.error().message;
      EXPECT_NE(doc.error().message.find("SYLVA_WITH_"), std::string::npos);
    }
  }
  auto status = sylva::scene::require_module("fog_machine", "x");
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().message.find("unknown module \"fog_machine\""), std::string::npos);
}

TEST(SceneDocument, ParametersByPath) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_text(R"({"ground": {}})", "p.json", warnings);
  ASSERT_TRUE(doc.ok());
  sylva::ParamRegistry params = doc->params();
  EXPECT_EQ(params.section_names(), (std::vector<std::string>{"camera", "sun", "wind", "environment", "render", "ground"}));
  ASSERT_TRUE(params.set("ground.noise.octaves", "4").ok());
  ASSERT_TRUE(params.set("sun.elevation_deg", "12.5").ok());
  EXPECT_EQ(doc->sun.elevation_deg, 12.5f);
  auto bad = params.set("ground.resolution", "abc");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("ground.resolution"), std::string::npos);
  EXPECT_EQ(doc->to_json()["ground"]["noise"]["octaves"], 4);
  // A copy is deep: changing it leaves the original alone.
  SceneDocument copy = *doc;
  ASSERT_TRUE(copy.params().set("ground.noise.octaves", "9").ok());
  EXPECT_EQ(doc->to_json()["ground"]["noise"]["octaves"], 4);
  EXPECT_EQ(copy.to_json()["ground"]["noise"]["octaves"], 9);
  // Adding a section twice is an error.
  EXPECT_FALSE(doc->add_module("ground").ok());
}

TEST(SceneDocument, DefaultSceneIsValidAndUsesWhatIsBuilt) {
  std::vector<std::string> warnings;
  auto doc = sylva::scene::default_scene(warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_TRUE(warnings.empty());
  EXPECT_TRUE(doc->has_module("terrain") || doc->has_module("ground"));
  // Terrain + forest + grass meadow wherever those modules are built in.
  EXPECT_EQ(doc->has_module("terrain"), sylva::scene::find_module("terrain") != nullptr);
  EXPECT_NE(doc->has_module("terrain"), doc->has_module("ground"));
  EXPECT_EQ(doc->has_module("grass"), sylva::scene::find_module("grass") != nullptr);
  EXPECT_EQ(doc->has_module("vegetation"), sylva::scene::find_module("vegetation") != nullptr);
  EXPECT_FALSE(doc->camera_paths.empty());
}

TEST(SceneDocument, ShippedScenesLoad) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(SYLVA_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    std::vector<std::string> warnings;
    auto text = sylva::read_file(entry.path());
    ASSERT_TRUE(text.ok());
    auto json = sylva::parse_json_text(*text, entry.path().string());
    ASSERT_TRUE(json.ok()) << json.error().message;
    bool needs_missing_module = false;
    for (const auto& [key, value] : json->items()) {
      (void)value;
      if (sylva::scene::is_known_module(key) && !sylva::scene::find_module(key)) needs_missing_module = true;
    }
    auto doc = SceneDocument::load(entry.path(), warnings);
    if (needs_missing_module) {
      EXPECT_FALSE(doc.ok()) << entry.path();
      continue;
    }
    ASSERT_TRUE(doc.ok()) << doc.error().message;
    EXPECT_TRUE(warnings.empty()) << entry.path() << ": " << (warnings.empty() ? "" : warnings[0]);
    ++count;
  }
  EXPECT_GE(count, 2);
}

// scenes/ holds one scene per module (that module alone) and a voxel world.
TEST(SceneDocument, ShippedScenesCoverEveryModule) {
  std::map<std::string, std::vector<std::string>> modules_of;  // file stem -> module sections
  for (const auto& entry : fs::directory_iterator(SYLVA_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    auto text = sylva::read_file(entry.path());
    ASSERT_TRUE(text.ok());
    auto json = sylva::parse_json_text(*text, entry.path().string());
    ASSERT_TRUE(json.ok()) << json.error().message;
    for (const auto& [key, value] : json->items()) {
      (void)value;
      if (sylva::scene::is_known_module(key)) modules_of[entry.path().stem().string()].push_back(key);
    }
  }
  for (std::string_view m : sylva::scene::known_modules()) {
    const std::string name(m);
    ASSERT_TRUE(modules_of.count(name)) << "scenes/" << name << ".json is missing";
    // The built-in ground (part of the scene module, in every build) may be the floor.
    std::vector<std::string> content = modules_of[name];
    if (name != "ground") std::erase(content, std::string("ground"));
    EXPECT_EQ(content, std::vector<std::string>{name}) << "scenes/" << name << ".json shows only " << name;
  }
  ASSERT_TRUE(modules_of.count("voxel_world"));
  EXPECT_EQ(modules_of["voxel_world"], std::vector<std::string>{"voxel"});
}

// A module that is built out (here simulated with ScopedBuiltOut, as the lean preset does for
// real) is refused by name and CMake option, never silently drawn as less.
TEST(SceneDocument, BuiltOutModuleIsAClearError) {
  for (std::string_view m : sylva::scene::known_modules()) {
    if (m == "ground" || !sylva::scene::find_module(m)) continue;
    const std::string name(m);
    sylva::scene::detail::ScopedBuiltOut out(name);
    EXPECT_EQ(sylva::scene::find_module(name), nullptr);
    std::vector<std::string> warnings;
    auto doc = SceneDocument::load(fs::path(SYLVA_SCENES_DIR) / (name + ".json"), warnings);
    ASSERT_FALSE(doc.ok()) << name;
    std::string upper = name == "model_terrain" ? std::string("terrain") : name;  // comes with the terrain module
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_NE(doc.error().message.find(name + ".json"), std::string::npos) << doc.error().message;
    EXPECT_NE(doc.error().message.find("built without the " + name + " module"), std::string::npos) << doc.error().message;
    EXPECT_NE(doc.error().message.find("-DSYLVA_WITH_" + upper + "=ON"), std::string::npos) << doc.error().message;
    // The default scene is assembled from what is built, so it still loads without the module.
    auto def = sylva::scene::default_scene(warnings);
    ASSERT_TRUE(def.ok()) << def.error().message;
    EXPECT_FALSE(def->has_module(name));
  }
  for (std::string_view m : sylva::scene::known_modules()) {
#if defined(SYLVA_HAS_TERRAIN) && defined(SYLVA_HAS_GRASS) && defined(SYLVA_HAS_VEGETATION) && defined(SYLVA_HAS_VOXEL)
    EXPECT_NE(sylva::scene::find_module(m), nullptr) << m << " is back after the scope";
#else
    (void)m;
#endif
  }
}
