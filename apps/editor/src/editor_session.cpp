#include "editor_session.hpp"

#include <sylva/render/gl_debug.hpp>

#include <sylva/core/log.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/scene/module_registry.hpp>

#if SYLVA_EDITOR_TREE_EXPORT
#include <sylva/vegetation/tree_export.hpp>
#endif

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace sylva::editor {

Result<std::unique_ptr<EditorSession>> EditorSession::create(glm::ivec2 viewport) {
  auto session = std::unique_ptr<EditorSession>(new EditorSession());
  SYLVA_TRY(session->set_viewport(viewport));
  SYLVA_TRY(session->new_scene());
  return session;
}

Status EditorSession::adopt(scene::SceneDocument document, std::optional<std::filesystem::path> path) {
  end_stroke();
  auto created = scene::Scene::create(std::move(document));
  if (!created.ok()) return created.error();
  scene_ = std::move(*created);
  path_ = std::move(path);
  history_.reset_saved();
  camera_ = scene_->make_camera(scene_->document().camera, viewport_);
  profiler_ = render::FrameProfiler();
  time_ = 0.0;
  watcher_ = SourceWatcher();
  watcher_.watch(scene_sources(scene_->document()));
  reloads_.clear();
  return {};
}

Status EditorSession::load(const std::filesystem::path& file) {
  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::load(file, warnings);
  if (!doc.ok()) return doc.error();
  SYLVA_TRY(adopt(std::move(*doc), file));
  warnings_ = std::move(warnings);
  return {};
}

Status EditorSession::new_scene() {
  warnings_.clear();
  return adopt(scene::SceneDocument{}, std::nullopt);
}

Status EditorSession::open_default() {
  std::vector<std::string> warnings;
  auto doc = scene::default_scene(warnings);
  if (!doc.ok()) return doc.error();
  SYLVA_TRY(adopt(std::move(*doc), std::nullopt));
  warnings_ = std::move(warnings);
  return {};
}

Status EditorSession::save() {
  if (!path_) return make_error(ErrorCode::kInvalidArgument, "the scene has no file yet; use save as");
  return save_as(*path_);
}

Status EditorSession::save_as(const std::filesystem::path& file) {
  end_stroke();
  // The document's camera is where the editor's camera is when saving.
  scene_->document().camera = scene::Scene::view_of(camera_);
  SYLVA_TRY(scene_->save(file));
  path_ = file;
  history_.mark_saved();
  return {};
}

Status EditorSession::set_param(const std::string& path, const std::string& text, bool merge) {
  auto before = scene_->get_param(path);
  if (!before.ok()) return before.error();
  SYLVA_TRY(scene_->set_param(path, text));
  const std::string after = scene_->get_param(path).value();
  if (after == *before) return {};
  if (merge) {
    if (UndoEntry* top = history_.mergeable_top(); top && top->edits.size() == 1) {
      if (auto* p = std::get_if<ParamEdit>(&top->edits[0]); p && p->path == path) {
        p->after = after;
        return {};
      }
    }
  }
  history_.push({"set " + path, {ParamEdit{path, *before, after}}});
  return {};
}

Status EditorSession::add_module(const std::string& name) {
  if (scene_->document().has_module(name)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("add_module {}: the scene already has it", name));
  }
  scene::SceneDocument probe;
  auto added = probe.add_module(name);
  if (!added.ok()) return added.error();
  const nlohmann::json section = probe.to_json()[name];
  SYLVA_TRY(write_section(name, section));
  history_.push({"add " + name, {SectionEdit{name, nullptr, section}}});
  return {};
}

Status EditorSession::remove_module(const std::string& name) {
  if (!scene_->document().has_module(name)) {
    return make_error(ErrorCode::kNotFound, fmt::format("remove_module {}: the scene has no such module", name));
  }
  const nlohmann::json section = scene_->document().to_json()[name];
  SYLVA_TRY(write_section(name, nullptr));
  history_.push({"remove " + name, {SectionEdit{name, section, nullptr}}});
  return {};
}

Status EditorSession::add_bookmark(const std::string& name) {
  if (name.empty() || name.find_first_of(". []=") != std::string::npos) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("bookmark \"{}\": use a name without spaces, dots or brackets", name));
  }
  std::optional<scene::CameraView> before;
  if (auto it = scene_->document().bookmarks.find(name); it != scene_->document().bookmarks.end()) before = it->second;
  const scene::CameraView view = scene::Scene::view_of(camera_);
  SYLVA_TRY(write_bookmark(name, view));
  history_.push({"bookmark " + name, {BookmarkEdit{name, before, view}}});
  return {};
}

Status EditorSession::remove_bookmark(const std::string& name) {
  auto it = scene_->document().bookmarks.find(name);
  if (it == scene_->document().bookmarks.end()) return make_error(ErrorCode::kNotFound, fmt::format("no bookmark \"{}\"", name));
  const scene::CameraView before = it->second;
  SYLVA_TRY(write_bookmark(name, std::nullopt));
  history_.push({"remove bookmark " + name, {BookmarkEdit{name, before, std::nullopt}}});
  return {};
}

std::vector<std::string> EditorSession::map_ids() const {
  std::vector<std::string> ids;
  for (const auto& [id, map] : const_cast<scene::Scene&>(*scene_).maps()) {
    if (scene_->document().has_module(map.module)) ids.push_back(id);
  }
  return ids;
}

std::vector<std::string> EditorSession::color_map_ids() const {
  const std::vector<std::string> ids = map_ids();
  std::vector<std::string> out;
  for (const std::string& id : ids) {
    if (!id.ends_with("_r")) continue;
    const std::string color = id.substr(0, id.size() - 2);
    const auto channels = color_channel_ids(color);
    if (std::all_of(channels.begin(), channels.end(), [&](const std::string& c) {
          return std::find(ids.begin(), ids.end(), c) != ids.end();
        })) {
      out.push_back(color);
    }
  }
  return out;
}

Status EditorSession::begin_stroke(const std::string& map_id, glm::dvec2 world_xz) {
  end_stroke();
  const std::vector<std::string> colors = color_map_ids();
  const bool color = std::find(colors.begin(), colors.end(), map_id) != colors.end();
  scene::SceneMap* map = color ? nullptr : scene_->map(map_id);
  if (!color && (!map || !scene_->document().has_module(map->module))) {
    std::string known;
    for (const std::string& id : map_ids()) known += (known.empty() ? "" : ", ") + id;
    for (const std::string& id : colors) known += ", " + id + " (colour)";
    return make_error(ErrorCode::kNotFound,
                      fmt::format("no map \"{}\" to paint (this scene has: {})", map_id, known.empty() ? "none" : known));
  }
  if (!(brush_.radius > 0.0f) || !std::isfinite(world_xz.x) || !std::isfinite(world_xz.y)) {
    return make_error(ErrorCode::kInvalidArgument, "stroke: the brush radius and the points must be positive/finite");
  }
  Stroke stroke{map_id, {}, world_xz};
  auto add_layer = [&](const std::string& id, scene::SceneMap& m, const BrushSettings& b) {
    stroke.layers.push_back({id, StrokeRecorder(id, m.grid), b, resolve_target(m.grid, b, world_xz)});
  };
  if (color) {
    const auto channels = color_channel_ids(map_id);
    for (int c = 0; c < 3; ++c) add_layer(channels[c], *scene_->map(channels[c]), color_channel_brush(brush_, c));
  } else {
    add_layer(map_id, *map, brush_);
  }
  stroke_.emplace(std::move(stroke));
  dab_to(world_xz);
  return {};
}

void EditorSession::dab_to(glm::dvec2 p) {
  std::vector<scene::TexelRect> changed(stroke_->layers.size());
  auto dab = [&](glm::dvec2 c) {
    for (std::size_t k = 0; k < stroke_->layers.size(); ++k) {
      StrokeLayer& layer = stroke_->layers[k];
      scene::SceneMap* map = scene_->map(layer.map_id);
      if (!map) continue;
      layer.recorder.before_dab(dab_rect(map->grid, c, layer.brush.radius));
      changed[k] = changed[k].unite(apply_dab(map->grid, map->kind, layer.brush, c, layer.target));
    }
  };
  const BrushSettings& b = brush_;
  if (p == stroke_->last_dab && stroke_->layers.front().recorder.rect().empty()) {
    dab(p);  // the first dab of the stroke
  } else {
    const std::vector<glm::dvec2> segment = {stroke_->last_dab, p};
    const std::vector<glm::dvec2> dabs = stroke_dabs(segment, std::max(0.01, static_cast<double>(b.spacing * b.radius)));
    for (std::size_t k = 1; k < dabs.size(); ++k) {
      dab(dabs[k]);
      stroke_->last_dab = dabs[k];
    }
  }
  for (std::size_t k = 0; k < changed.size(); ++k) {
    if (changed[k].empty()) continue;
    Status s = scene_->map_changed(stroke_->layers[k].map_id, changed[k]);
    if (!s.ok()) log_warn("editor: {}", s.error().message);
  }
}

Status EditorSession::continue_stroke(glm::dvec2 world_xz) {
  if (!stroke_) return make_error(ErrorCode::kInvalidArgument, "no stroke in progress");
  if (!std::isfinite(world_xz.x) || !std::isfinite(world_xz.y)) return {};
  dab_to(world_xz);
  return {};
}

void EditorSession::end_stroke() {
  if (!stroke_) return;
  UndoEntry entry{"paint " + stroke_->map_id, {}};
  for (const StrokeLayer& layer : stroke_->layers) {
    if (auto edit = layer.recorder.finish()) entry.edits.push_back(std::move(*edit));
  }
  if (!entry.edits.empty()) history_.push(std::move(entry));  // a colour stroke: its three maps, one step
  stroke_.reset();
}

Status EditorSession::stroke(const std::string& map_id, const std::vector<glm::dvec2>& points) {
  if (points.empty()) return make_error(ErrorCode::kInvalidArgument, "stroke: no points");
  SYLVA_TRY(begin_stroke(map_id, points.front()));
  for (std::size_t k = 1; k < points.size(); ++k) SYLVA_TRY(continue_stroke(points[k]));
  end_stroke();
  return {};
}

void EditorSession::set_camera(const scene::CameraView& view) { camera_ = scene_->make_camera(view, viewport_); }

Status EditorSession::go_to_bookmark(const std::string& name) {
  auto it = scene_->document().bookmarks.find(name);
  if (it == scene_->document().bookmarks.end()) {
    return make_error(ErrorCode::kNotFound, fmt::format("no bookmark \"{}\" in this scene", name));
  }
  set_camera(it->second);
  return {};
}

Status EditorSession::set_viewport(glm::ivec2 size) {
  size = glm::max(size, glm::ivec2(16));
  if (framebuffer_ && size == viewport_) return {};
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA8}});
  if (!fb.ok()) return fb.error();
  framebuffer_ = std::move(*fb);
  viewport_ = size;
  camera_.set_aspect(size.x, size.y);
  return {};
}

void EditorSession::poll_sources(bool now) {
  const auto t = std::chrono::steady_clock::now();
  if (!now && t < next_poll_) return;
  next_poll_ = t + std::chrono::milliseconds(500);
  watcher_.watch(scene_sources(scene_->document()));
  // The changed files by module, so a module whose grammar and table both changed rebuilds once.
  std::map<std::string, std::vector<WatchedSource>> by_module;
  for (const WatchedSource& w : watcher_.poll()) by_module[w.param.substr(0, w.param.find('.'))].push_back(w);
  for (const auto& [module, changed] : by_module) {
    std::vector<std::pair<LogLevel, std::string>> logged;
    set_log_sink([&](LogLevel level, std::string_view text) { logged.emplace_back(level, std::string(text)); });
    const Status reloaded = scene_->reload_module(module);
    set_log_sink(nullptr);
    for (const WatchedSource& w : changed) {
      ++reloads_[w.file];
      messages_.push_back(fmt::format("reloaded {} ({})", w.file.string(), w.param));
    }
    for (const auto& [level, text] : logged) {
      log_message(level, text);  // still on stderr as before
      if (level >= LogLevel::kWarn) messages_.push_back("warning: " + text);
    }
    if (!reloaded.ok()) messages_.push_back(fmt::format("error: reloading {}: {}", module, reloaded.error().message));
  }
  if (!by_module.empty()) watcher_.watch(scene_sources(scene_->document()));  // the files the new contents name
}

int EditorSession::reloads(const std::filesystem::path& file) const {
  std::error_code ec;
  const std::filesystem::path a = std::filesystem::absolute(file, ec);
  auto it = reloads_.find((ec ? file : a).lexically_normal());
  return it == reloads_.end() ? 0 : it->second;
}

Status EditorSession::render_frame(double dt) {
  poll_sources();
  const std::size_t mark = render::gl_error_mark();
  time_ += std::max(dt, 0.0);
  scene_->update(camera_, time_, static_cast<float>(std::max(dt, 0.0)), viewport_);
  scene_->render(framebuffer_, profiler_);
  return render::check_frame_gl_errors(mark, "the frame");
}

Result<std::string> EditorSession::export_tree(const std::filesystem::path& folder) {
#if !SYLVA_EDITOR_TREE_EXPORT
  (void)folder;
  return make_error(ErrorCode::kUnsupported, "the editor was built without the vegetation module (no tree export)");
#else
  if (scene_->module("vegetation") == nullptr)
    return make_error(ErrorCode::kNotFound, "the scene has no vegetation section (no forest to export a tree from)");
  const auto param = [&](const std::string& path) { return scene_->get_param("vegetation." + path); };
  const auto number = [&](const std::string& path, auto fallback) {
    auto text = param(path);
    auto v = fallback;
    if (text.ok()) std::from_chars(text->data(), text->data() + text->size(), v);
    return v;
  };
  const int texture_size = number("leaf_texture_size", 128);
  std::optional<Result<vegetation::ExportTree>> tree;
  for (int k = 0; k < 4 && !tree; ++k) {
    auto file = param(fmt::format("species_files.{}.file", k));
    if (!file.ok() || file->empty()) continue;
    std::vector<std::string> warnings;
    tree = vegetation::export_tree_from_species_file(scene_->document().resolve(*file), texture_size, warnings);
    for (const std::string& w : warnings) log_warn("export tree: {}", w);
  }
  if (!tree) {
    auto preset = param("species");
    const auto seed = number("species_seed", std::uint32_t{1});
    for (const auto& e : enum_names(vegetation::SpeciesPreset{}))
      if (preset.ok() && *preset == e.name) tree = vegetation::export_tree_from_preset(e.value, seed, texture_size);
    if (!tree) return make_error(ErrorCode::kNotFound, "the forest names no species to export");
  }
  if (!tree->ok()) return tree->error();
  vegetation::TreeExportOptions options;
  for (const ParamDescriptor& p : describe_params(options.mesh)) {
    auto v = param("mesh." + p.path);
    if (v.ok()) SYLVA_TRY(::sylva::set_param(options.mesh, p.path, *v));
  }
  Result<vegetation::BakedTree> baked = vegetation::bake_export_slices(
      **tree, options, number("forest.lod.slice_resolution", 128), number("forest.lod.slice_margin", 0.12f));
  if (!baked.ok()) return baked.error();
  Result<vegetation::TreeExportReport> report = vegetation::export_tree(**tree, folder, options, &*baked);
  if (!report.ok()) return report.error();
  return fmt::format("exported '{}' to {}: {} files, {} + {} triangles, {} slice layers", (*tree)->name, folder.string(),
                     report->files.size(), report->bark_triangles, report->leaf_triangles, report->slice_layers);
#endif
}

Status EditorSession::screenshot(const std::filesystem::path& file, std::optional<glm::ivec2> size) {
  if (!size || *size == viewport_) {
    SYLVA_TRY(render_frame(0.0));
    return render::save_screenshot(framebuffer_, file);
  }
  auto fb = render::Framebuffer::create({.width = size->x, .height = size->y, .color_formats = {GL_RGBA8}});
  if (!fb.ok()) return fb.error();
  render::Camera camera = camera_;
  camera.set_aspect(size->x, size->y);
  const std::size_t mark = render::gl_error_mark();
  scene_->update(camera, time_, 0.0f, *size);
  scene_->render(*fb, profiler_);
  SYLVA_TRY(render::check_frame_gl_errors(mark, "the screenshot frame"));
  return render::save_screenshot(*fb, file);
}

std::optional<glm::dvec3> EditorSession::pick_ground(glm::vec2 pixel) const {
  const glm::vec2 ndc(2.0f * (pixel.x + 0.5f) / static_cast<float>(viewport_.x) - 1.0f,
                      1.0f - 2.0f * (pixel.y + 0.5f) / static_cast<float>(viewport_.y));
  const glm::mat4 inv = glm::inverse(camera_.view_projection());
  // Reversed-Z: depth 1 is the near plane, 0.5 a finite point beyond it.
  const glm::vec4 a = inv * glm::vec4(ndc, 1.0f, 1.0f), b = inv * glm::vec4(ndc, 0.5f, 1.0f);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(glm::vec3(b) / b.w - glm::vec3(a) / a.w));
  const glm::dvec3 origin = camera_.position();
  const HeightField* ground = scene_->ground();
  auto above = [&](double t) {
    const glm::dvec3 p = origin + dir * t;
    return p.y - (ground ? ground->height(p.x, p.z) : 0.0);
  };
  if (!ground) {
    if (std::abs(dir.y) < 1e-9) return std::nullopt;
    const double t = -origin.y / dir.y;
    if (t <= 0.0) return std::nullopt;
    return origin + dir * t;
  }
  const double base = 0.5 * ground->spacing();
  double t0 = 0.0, f0 = above(0.0);
  if (f0 < 0.0) return std::nullopt;  // under the ground
  for (double t = base; t < 2.0e5; t += std::max(base, 0.002 * t)) {
    const double f = above(t);
    if (f <= 0.0) {
      double lo = t0, hi = t;
      for (int k = 0; k < 40; ++k) {
        const double mid = 0.5 * (lo + hi);
        (above(mid) > 0.0 ? lo : hi) = mid;
      }
      return origin + dir * hi;
    }
    t0 = t;
    f0 = f;
  }
  return std::nullopt;
}

Status EditorSession::write_map_rect(const std::string& map_id, const scene::TexelRect& rect, const std::vector<float>& values) {
  scene::SceneMap* map = scene_->map(map_id);
  if (!map) return make_error(ErrorCode::kNotFound, fmt::format("map \"{}\" no longer exists", map_id));
  const scene::TexelRect r = rect.intersect(map->grid.bounds());
  if (static_cast<std::size_t>(r.width()) * static_cast<std::size_t>(r.height()) != values.size() || !(r == rect)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("map \"{}\" changed size since the edit", map_id));
  }
  map->grid.paste_rect(rect, values);
  return scene_->map_changed(map_id, rect);
}

Status EditorSession::write_param(const std::string& path, const std::string& text) { return scene_->set_param(path, text); }

Status EditorSession::write_section(const std::string& module, const nlohmann::json& section) {
  nlohmann::json j = scene_->document().to_json();
  if (section.is_null()) j.erase(module);
  else j[module] = section;
  std::vector<std::string> warnings;
  auto doc = scene::SceneDocument::from_json(j, "scene", warnings);
  if (!doc.ok()) return doc.error();
  doc->set_directory(scene_->document().directory());
  if (!scene_->document().file().empty()) doc->set_file(scene_->document().file());
  return scene_->replace_document(std::move(*doc));
}

Status EditorSession::write_bookmark(const std::string& name, const std::optional<scene::CameraView>& view) {
  if (view) scene_->document().bookmarks[name] = *view;
  else scene_->document().bookmarks.erase(name);
  return {};
}

}  // namespace sylva::editor
