#pragma once
// A scene file as data (GL-free): what sylva-player plays, sylva-editor edits and sylva-bench
// sweeps. Versioned JSON, one section per module the scene uses:
//
//   {
//     "sylva_scene": 1,                      // format version (missing = 1)
//     "name": "Meadow",
//     "camera":      {CameraView},           // where the player starts
//     "sun":         {SunSettings},          // environment.hpp
//     "wind":        {WindSettings},         // core/wind.hpp: the one wind of the scene
//     "environment": {EnvironmentSettings},  // time of day, season, latitude
//     "render":      {SceneRenderSettings},  // shadows, tone mapping
//     "bookmarks":   {"<name>": {CameraView}, ...},
//     "camera_paths": {"<name>": {"interpolation": "catmull_rom", "loop": false,
//                                 "keys": [{"time_s": 0, CameraView fields...}, ...]}, ...},
//     "terrain": {... its settings ..., "maps": {"height": "maps/height.exr"}},
//     "grass":   {..., "maps": {"density": "maps/density.png"}},
//     ...
//   }
//
// Every settings object is loaded through core parameter reflection (params_json.hpp), so a
// parameter's JSON path is also its --set path ("grass.field.density"). Map paths are relative
// to the scene file's folder.
//
// Loading rules:
//  - Errors (kParse for malformed JSON with file:line:column, kInvalidArgument / kNotFound for
//    content) name the JSON path: "grass.blade.height_max: 20 is above the maximum 10",
//    "camera_paths.fly.keys[2].time_s: ...". All content errors are reported together.
//  - A module section for a module this program was built without is an error naming the module
//    (module_registry.hpp); only the sections present are part of the scene.
//  - Unknown keys anywhere are not errors: each is reported as a warning (with a "did you mean"
//    when a known key is close) and kept, so saving writes them back unchanged.
//  - Missing keys keep their defaults.
// Saving writes every known value (lossless: floats round-trip bit-exactly) plus the unknown
// keys, through an atomic write (a failed save never damages the previous file).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/scene/camera_path.hpp>
#include <sylva/scene/environment.hpp>
#include <sylva/scene/module_settings.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

inline constexpr int kSceneFormatVersion = 1;

// Whether a setting (its path inside its section, "flora.species_file") names a file relative to
// the scene file: by the scenes' convention its last name is `file` or ends in `_file`.
bool names_scene_file(std::string_view path);

struct ModuleSection {
  std::string name;                          // module name = section key
  std::unique_ptr<ModuleSettings> settings;  // never null
  std::map<std::string, std::string> maps;   // slot -> file path relative to the scene file
};

class SceneDocument {
 public:
  // An empty scene: sky only, default camera, sun, wind and environment.
  SceneDocument() = default;
  SceneDocument(const SceneDocument& other);
  SceneDocument& operator=(const SceneDocument& other);
  SceneDocument(SceneDocument&&) noexcept = default;
  SceneDocument& operator=(SceneDocument&&) noexcept = default;

  // `source` names the document in messages (a file name, "<embedded default scene>").
  static Result<SceneDocument> from_json(const nlohmann::json& json, std::string_view source,
                                         std::vector<std::string>& warnings);
  static Result<SceneDocument> from_text(std::string_view text, std::string_view source,
                                         std::vector<std::string>& warnings);
  // Reads a file; directory() becomes the file's folder. Messages start with the file name.
  static Result<SceneDocument> load(const std::filesystem::path& file, std::vector<std::string>& warnings);

  nlohmann::json to_json() const;
  std::string to_text() const;  // to_json() pretty-printed, newline-terminated
  // Writes to_text() atomically (maps are written by Scene::save / the editor).
  Status save(const std::filesystem::path& file) const;

  // The folder map paths are relative to ("" = the working directory).
  const std::filesystem::path& directory() const { return directory_; }
  void set_directory(std::filesystem::path directory) { directory_ = std::move(directory); }
  // The file this document was loaded from or last saved to ("" = none yet, e.g. the embedded
  // default). set_file() also makes its folder the directory(). Scene::save tells a "save as"
  // (another file: maps are copied to the new scene's own map folder) from a save by it.
  const std::filesystem::path& file() const { return file_; }
  void set_file(std::filesystem::path file) {
    directory_ = file.parent_path();
    file_ = std::move(file);
  }
  // directory() / relative, or `relative` itself when it is absolute.
  std::filesystem::path resolve(const std::string& relative) const;

  // Module sections, in known_modules() order.
  const std::vector<ModuleSection>& modules() const { return modules_; }
  std::vector<ModuleSection>& modules() { return modules_; }
  ModuleSection* module(std::string_view name);
  const ModuleSection* module(std::string_view name) const;
  bool has_module(std::string_view name) const { return module(name) != nullptr; }
  // Adds a section with default settings. Errors: built out or unknown (require_module), or
  // already present.
  Result<ModuleSection*> add_module(std::string_view name);
  bool remove_module(std::string_view name);

  // Every parameter of the scene, sections "camera", "sun", "wind", "environment", "render",
  // then the modules. The registry points into this document: use it while the document lives and is
  // not moved (Scene keeps its document at a stable address).
  ParamRegistry params();
  // Ranges of every parameter, cross-field module checks, bookmarks and camera paths, and the
  // one-ground rule (terrain and ground exclude each other). All problems, one per line.
  Status validate() const;

  // Unknown keys kept for saving: {"<JSON pointer>": value}, e.g. {"/grass/colour": "green"}.
  const nlohmann::json& unknown() const { return unknown_; }

  std::string name;
  CameraView camera{{-620.0, 260.0, 700.0}, -40.0f, -12.0f, 60.0f, HeightMode::kAbsolute};
  SunSettings sun;
  WindSettings wind;
  EnvironmentSettings environment;
  SceneRenderSettings render;
  std::map<std::string, CameraView> bookmarks;
  std::map<std::string, CameraPath> camera_paths;

 private:
  nlohmann::json known_json() const;

  std::vector<ModuleSection> modules_;
  std::filesystem::path directory_;
  std::filesystem::path file_;
  nlohmann::json unknown_ = nlohmann::json::object();
};

// The scene played when none is given: terrain + forest + grass meadow as far as those modules
// are built in; otherwise the plain ground with what is available. Valid JSON of this format.
std::string default_scene_text();
// Parsed default scene (never fails for a correct build; errors would name the embedded text).
Result<SceneDocument> default_scene(std::vector<std::string>& warnings);

// Keys of `raw` that `known` lacks, recursively (objects; arrays element-wise when both have
// the same length), as {"<JSON pointer>": value}. Each one is reported in `warnings` as
// "<path>: unknown key, kept when saving" with a "did you mean" for a close known sibling.
nlohmann::json collect_unknown_keys(const nlohmann::json& raw, const nlohmann::json& known, const std::string& path,
                                    std::vector<std::string>& warnings);
// Adds the unknown keys back into `out` where their parent object still exists (a removed
// section or bookmark takes its unknown keys with it).
void merge_unknown_keys(nlohmann::json& out, const nlohmann::json& unknown);

}  // namespace sylva::scene
