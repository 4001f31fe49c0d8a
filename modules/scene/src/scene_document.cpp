#include <sylva/scene/scene_document.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/scene/module_registry.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::scene {
namespace {

constexpr std::string_view kVersionKey = "sylva_scene";

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

const char* json_type(const nlohmann::json& j) { return j.type_name(); }

Error content_error(std::string message) { return make_error(ErrorCode::kInvalidArgument, std::move(message)); }

// Loads a Visitable from the object at `path`; a non-object is an error naming the path.
template <class T>
void load_object(T& target, const nlohmann::json& json, const std::string& path, std::vector<std::string>& errors) {
  if (!json.is_object()) {
    errors.push_back(fmt::format("{}: expected an object, got {}", path, json_type(json)));
    return;
  }
  std::vector<std::string> ignored;  // unknown keys are reported by collect_unknown_keys
  Status s = params_from_json(target, json, ignored, path);
  if (!s.ok()) errors.push_back(s.error().message);
}

void load_path(CameraPath& path, const nlohmann::json& json, const std::string& where, std::vector<std::string>& errors) {
  if (!json.is_object()) {
    errors.push_back(fmt::format("{}: expected an object, got {}", where, json_type(json)));
    return;
  }
  nlohmann::json scalars = json;
  scalars.erase("keys");
  load_object(path.settings, scalars, where, errors);
  auto keys = json.find("keys");
  if (keys == json.end()) {
    errors.push_back(fmt::format("{}.keys: missing (a camera path needs at least one key)", where));
    return;
  }
  if (!keys->is_array()) {
    errors.push_back(fmt::format("{}.keys: expected an array, got {}", where, json_type(*keys)));
    return;
  }
  for (std::size_t i = 0; i < keys->size(); ++i) {
    CameraKey key;
    const std::size_t before = errors.size();
    load_object(key, (*keys)[i], fmt::format("{}.keys[{}]", where, i), errors);
    if (errors.size() == before) path.keys.push_back(key);
  }
  if (path.keys.size() == keys->size()) {
    Status s = path.validate(where);
    if (!s.ok()) errors.push_back(s.error().message);
  }
}

nlohmann::json path_to_json(const CameraPath& path) {
  nlohmann::json j = params_to_json(path.settings);
  nlohmann::json keys = nlohmann::json::array();
  for (const CameraKey& k : path.keys) keys.push_back(params_to_json(k));
  j["keys"] = std::move(keys);
  return j;
}

void load_module(ModuleSection& section, const nlohmann::json& json, std::vector<std::string>& errors) {
  if (!json.is_object()) {
    errors.push_back(fmt::format("{}: expected an object, got {}", section.name, json_type(json)));
    return;
  }
  nlohmann::json params = json;
  params.erase("maps");
  load_object(*section.settings, params, section.name, errors);
  auto maps = json.find("maps");
  if (maps == json.end()) return;
  const std::string maps_path = section.name + ".maps";
  if (!maps->is_object()) {
    errors.push_back(fmt::format("{}: expected an object of slot: file path, got {}", maps_path, json_type(*maps)));
    return;
  }
  const std::vector<MapSlot> slots = section.settings->map_slots();
  for (const auto& [slot, value] : maps->items()) {
    // An init-capture, not [&]: clang 14 (the fuzz build) cannot capture a structured binding.
    const bool known = std::any_of(slots.begin(), slots.end(), [&key = slot](const MapSlot& s) { return key == s.name; });
    if (!known) continue;  // reported and kept as an unknown key
    if (!value.is_string() || value.get<std::string>().empty()) {
      errors.push_back(fmt::format("{}.{}: expected a non-empty file path string, got {}", maps_path, slot,
                                   value.is_string() ? "an empty string" : json_type(value)));
      continue;
    }
    section.maps[slot] = value.get<std::string>();
  }
}

std::size_t module_order(std::string_view name) {
  const auto known = known_modules();
  return static_cast<std::size_t>(std::find(known.begin(), known.end(), name) - known.begin());
}

}  // namespace

SceneDocument::SceneDocument(const SceneDocument& other)
    : name(other.name),
      camera(other.camera),
      sun(other.sun),
      wind(other.wind),
      environment(other.environment),
      render(other.render),
      bookmarks(other.bookmarks),
      camera_paths(other.camera_paths),
      directory_(other.directory_),
      file_(other.file_),
      unknown_(other.unknown_) {
  for (const ModuleSection& s : other.modules_) modules_.push_back({s.name, s.settings->clone(), s.maps});
}

SceneDocument& SceneDocument::operator=(const SceneDocument& other) {
  if (this != &other) {
    SceneDocument copy(other);
    *this = std::move(copy);
  }
  return *this;
}

Result<SceneDocument> SceneDocument::from_json(const nlohmann::json& json, std::string_view source,
                                               std::vector<std::string>& warnings) {
  if (!json.is_object()) {
    return make_error(ErrorCode::kParse, fmt::format("{}: a scene file must hold a JSON object, got {}", source, json_type(json)));
  }
  SceneDocument doc;
  std::vector<std::string> errors;

  if (auto v = json.find(kVersionKey); v != json.end()) {
    if (!v->is_number_integer() && !v->is_number_unsigned()) {
      errors.push_back(fmt::format("{}: expected the format version as a whole number, got {}", kVersionKey, v->dump()));
    } else if (v->get<std::int64_t>() > kSceneFormatVersion) {
      errors.push_back(fmt::format("{}: version {} is newer than this program reads ({}); update Sylva", kVersionKey,
                                   v->get<std::int64_t>(), kSceneFormatVersion));
    } else if (v->get<std::int64_t>() < 1) {
      errors.push_back(fmt::format("{}: version {} does not exist (versions start at 1)", kVersionKey, v->get<std::int64_t>()));
    }
  }

  for (const auto& [key, value] : json.items()) {
    if (key == kVersionKey) continue;
    if (key == "name") {
      if (!value.is_string()) errors.push_back(fmt::format("name: expected a string, got {}", json_type(value)));
      else doc.name = value.get<std::string>();
    } else if (key == "camera") {
      load_object(doc.camera, value, key, errors);
    } else if (key == "sun") {
      load_object(doc.sun, value, key, errors);
    } else if (key == "wind") {
      load_object(doc.wind, value, key, errors);
    } else if (key == "environment") {
      load_object(doc.environment, value, key, errors);
    } else if (key == "render") {
      load_object(doc.render, value, key, errors);
    } else if (key == "bookmarks") {
      if (!value.is_object()) {
        errors.push_back(fmt::format("bookmarks: expected an object of name: camera view, got {}", json_type(value)));
        continue;
      }
      for (const auto& [bookmark, view_json] : value.items()) {
        CameraView view;
        const std::size_t before = errors.size();
        load_object(view, view_json, "bookmarks." + bookmark, errors);
        if (errors.size() == before) doc.bookmarks[bookmark] = view;
      }
    } else if (key == "camera_paths") {
      if (!value.is_object()) {
        errors.push_back(fmt::format("camera_paths: expected an object of name: path, got {}", json_type(value)));
        continue;
      }
      for (const auto& [path_name, path_json] : value.items()) {
        CameraPath path;
        const std::size_t before = errors.size();
        load_path(path, path_json, "camera_paths." + path_name, errors);
        if (errors.size() == before) doc.camera_paths[path_name] = std::move(path);
      }
    } else if (is_known_module(key)) {
      auto added = doc.add_module(key);
      if (!added.ok()) {
        errors.push_back(added.error().message);
        continue;
      }
      load_module(**added, value, errors);
    }
    // Anything else is an unknown key: reported and kept below.
  }

  if (errors.empty()) {
    Status valid = doc.validate();
    if (!valid.ok()) errors.push_back(valid.error().message);
  }
  if (!errors.empty()) {
    std::string all;
    for (const std::string& e : errors) all += (all.empty() ? "" : "\n") + fmt::format("{}: {}", source, e);
    return content_error(std::move(all));
  }

  std::vector<std::string> unknown_warnings;
  doc.unknown_ = collect_unknown_keys(json, doc.known_json(), "", unknown_warnings);
  for (std::string& w : unknown_warnings) warnings.push_back(fmt::format("{}: {}", source, w));
  return doc;
}

Result<SceneDocument> SceneDocument::from_text(std::string_view text, std::string_view source,
                                               std::vector<std::string>& warnings) {
  auto json = parse_json_text(text, source);
  if (!json.ok()) return json.error();
  return from_json(*json, source, warnings);
}

Result<SceneDocument> SceneDocument::load(const std::filesystem::path& file, std::vector<std::string>& warnings) {
  auto text = read_file(file);
  if (!text.ok()) return text.error();
  auto doc = from_text(*text, file.string(), warnings);
  if (!doc.ok()) return doc.error();
  doc->set_file(file);
  return doc;
}

nlohmann::json SceneDocument::known_json() const {
  nlohmann::json j = nlohmann::json::object();
  j[std::string(kVersionKey)] = kSceneFormatVersion;
  if (!name.empty()) j["name"] = name;
  j["camera"] = params_to_json(camera);
  j["sun"] = params_to_json(sun);
  j["wind"] = params_to_json(wind);
  j["environment"] = params_to_json(environment);
  j["render"] = params_to_json(render);
  if (!bookmarks.empty()) {
    nlohmann::json b = nlohmann::json::object();
    for (const auto& [n, view] : bookmarks) b[n] = params_to_json(view);
    j["bookmarks"] = std::move(b);
  }
  if (!camera_paths.empty()) {
    nlohmann::json p = nlohmann::json::object();
    for (const auto& [n, path] : camera_paths) p[n] = path_to_json(path);
    j["camera_paths"] = std::move(p);
  }
  for (const ModuleSection& s : modules_) {
    nlohmann::json m = params_to_json(*s.settings);
    if (!m.is_object()) m = nlohmann::json::object();
    if (!s.maps.empty()) {
      nlohmann::json maps = nlohmann::json::object();
      for (const auto& [slot, path] : s.maps) maps[slot] = path;
      m["maps"] = std::move(maps);
    }
    j[s.name] = std::move(m);
  }
  return j;
}

nlohmann::json SceneDocument::to_json() const {
  nlohmann::json j = known_json();
  merge_unknown_keys(j, unknown_);
  return j;
}

std::string SceneDocument::to_text() const { return to_json().dump(2) + "\n"; }

Status SceneDocument::save(const std::filesystem::path& file) const { return write_file_atomic(file, to_text()); }

std::filesystem::path SceneDocument::resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  if (p.is_absolute() || directory_.empty()) return p;
  return directory_ / p;
}

ModuleSection* SceneDocument::module(std::string_view name) {
  for (ModuleSection& s : modules_) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const ModuleSection* SceneDocument::module(std::string_view name) const {
  return const_cast<SceneDocument*>(this)->module(name);
}

Result<ModuleSection*> SceneDocument::add_module(std::string_view name) {
  SYLVA_TRY(require_module(name, name));
  if (has_module(name)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: the scene already has this module", name));
  }
  const ModuleDescriptor* d = find_module(name);
  ModuleSection section{std::string(name), d->make_settings(), {}};
  const std::size_t order = module_order(name);
  auto pos = std::find_if(modules_.begin(), modules_.end(), [&](const ModuleSection& s) { return module_order(s.name) > order; });
  pos = modules_.insert(pos, std::move(section));
  return &*pos;
}

bool SceneDocument::remove_module(std::string_view name) {
  auto it = std::find_if(modules_.begin(), modules_.end(), [&](const ModuleSection& s) { return s.name == name; });
  if (it == modules_.end()) return false;
  modules_.erase(it);
  return true;
}

ParamRegistry SceneDocument::params() {
  ParamRegistry r;
  r.add("camera", camera);
  r.add("sun", sun);
  r.add("wind", wind);
  r.add("environment", environment);
  r.add("render", render);
  for (ModuleSection& s : modules_) r.add(s.name, *s.settings);
  return r;
}

Status SceneDocument::validate() const {
  std::vector<std::string> problems;
  auto check = [&](Status s) {
    if (!s.ok()) problems.push_back(s.error().message);
  };
  check(validate_params(camera, "camera"));
  check(validate_params(sun, "sun"));
  check(validate_params(wind, "wind"));
  check(validate_params(environment, "environment"));
  check(validate_params(render, "render"));
  if (const int m = render.msaa_samples; m != 1 && m != 2 && m != 4 && m != 8) {
    problems.push_back(fmt::format("render.msaa_samples: {} is not 1, 2, 4 or 8", m));
  }
  for (const auto& [n, view] : bookmarks) check(validate_params(view, "bookmarks." + n));
  for (const auto& [n, path] : camera_paths) check(path.validate("camera_paths." + n));
  int grounds = 0;
  for (const ModuleSection& s : modules_) {
    check(validate_params(*s.settings, s.name));
    check(s.settings->check(s.name));
    if (const ModuleDescriptor* d = find_module(s.name); d && d->provides_ground) ++grounds;
  }
  if (grounds > 1) {
    problems.push_back("ground: a scene has one ground; \"terrain\" and \"ground\" both provide it, keep one");
  }
  if (problems.empty()) return {};
  std::string all;
  for (const std::string& p : problems) all += (all.empty() ? "" : "\n") + p;
  return content_error(std::move(all));
}

namespace {

void collect_unknown(const nlohmann::json& raw, const nlohmann::json& known, const std::string& path,
                     const nlohmann::json::json_pointer& pointer, nlohmann::json& out, std::vector<std::string>& warnings) {
  if (raw.is_object() && known.is_object()) {
    for (const auto& [key, value] : raw.items()) {
      const std::string here = join_path(path, key);
      auto k = known.find(key);
      if (k != known.end()) {
        collect_unknown(value, *k, here, pointer / key, out, warnings);
        continue;
      }
      std::vector<std::string> candidates;
      for (const auto& item : known.items()) candidates.push_back(item.key());
      if (path.empty()) {
        // Top level: sections that are absent from this document are still valid keys.
        for (const char* k : {"name", "camera", "sun", "wind", "environment", "render", "bookmarks", "camera_paths"}) candidates.push_back(k);
        for (std::string_view m : known_modules()) candidates.emplace_back(m);
      }
      std::string suggestion;
      std::size_t best = key.size() / 3 + 1;
      for (const std::string& candidate : candidates) {
        const std::size_t d = edit_distance(key, candidate);
        if (d <= best && d < key.size()) {
          best = d;
          suggestion = candidate;
        }
      }
      warnings.push_back(suggestion.empty()
                             ? fmt::format("{}: unknown key, kept when saving", here)
                             : fmt::format("{}: unknown key, kept when saving (did you mean \"{}\"?)", here, suggestion));
      out[(pointer / key).to_string()] = value;
    }
  } else if (raw.is_array() && known.is_array() && raw.size() == known.size()) {
    for (std::size_t i = 0; i < raw.size(); ++i) {
      collect_unknown(raw[i], known[i], fmt::format("{}[{}]", path, i), pointer / i, out, warnings);
    }
  }
}

}  // namespace

nlohmann::json collect_unknown_keys(const nlohmann::json& raw, const nlohmann::json& known, const std::string& path,
                                    std::vector<std::string>& warnings) {
  nlohmann::json out = nlohmann::json::object();
  collect_unknown(raw, known, path, nlohmann::json::json_pointer(), out, warnings);
  return out;
}

void merge_unknown_keys(nlohmann::json& out, const nlohmann::json& unknown) {
  for (const auto& [pointer_text, value] : unknown.items()) {
    const nlohmann::json::json_pointer pointer(pointer_text);
    const nlohmann::json::json_pointer parent = pointer.parent_pointer();
    // Only where the parent object still exists: a removed section takes its unknown keys with it.
    if (!out.contains(parent)) continue;
    nlohmann::json& container = out[parent];
    if (!container.is_object()) continue;
    container[pointer.back()] = value;
  }
}

}  // namespace sylva::scene
