#include "terrain_import.hpp"

#include "editor_session.hpp"

#include <sylva/core/params.hpp>
#if SYLVA_EDITOR_TERRAIN_IMPORT
#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/mesh.hpp>
#endif

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace sylva::editor {
namespace fs = std::filesystem;

namespace {

bool is_mesh(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".obj" || ext == ".iv" || ext == ".gltf" || ext == ".glb";
}

// Settings of a struct read back from the scene's parameters under `prefix` (a section that does
// not exist yet keeps the defaults).
template <class T>
void settings_from_scene(T& settings, scene::Scene& scene, const std::string& prefix) {
  for (const ParamDescriptor& p : describe_params(settings)) {
    auto text = scene.get_param(prefix + p.path);
    if (text.ok()) (void)::sylva::set_param(settings, p.path, *text);
  }
}

// A path as the scene stores it: relative to the scene file's folder (directory() "" is the
// working directory), absolute for a scene without a file (save as rebases it).
std::string scene_relative(const scene::SceneDocument& doc, const fs::path& file) {
  std::error_code ec;
  const fs::path abs = fs::absolute(file, ec).lexically_normal();
  if (doc.file().empty()) return abs.generic_string();
  const fs::path folder = doc.directory().empty() ? fs::current_path(ec) : fs::absolute(doc.directory(), ec);
  const fs::path rel = abs.lexically_relative(folder.lexically_normal());
  return rel.empty() ? abs.generic_string() : rel.generic_string();
}

}  // namespace

std::string TerrainSourceInfo::summary() const {
  if (kind == Kind::kMesh) return fmt::format("{} (mesh): {} vertices, {} faces", file.string(), vertices, faces);
  return fmt::format("{} ({}{}): {} x {} samples, {:g} m apart (file {:g} x {:g} m), heights {:.1f} to {:.1f} m, {} nodata filled",
                     file.string(), reader, crs.empty() ? "" : ", " + crs, columns, rows, spacing, source_spacing_x,
                     source_spacing_z, min_height, max_height, nodata_filled);
}

TerrainImport::~TerrainImport() {
  cancel();
  join();
}

void TerrainImport::join() {
  if (worker_.joinable()) worker_.join();
}

void TerrainImport::release() {
  {
    std::lock_guard<std::mutex> lock(hold_mutex_);
    hold_ = false;
  }
  hold_cv_.notify_all();
}

void TerrainImport::wait_until_held() {
  std::unique_lock<std::mutex> lock(hold_mutex_);
  hold_cv_.wait(lock, [this] { return held_ || done_ || state_ != State::kBaking; });
}

void TerrainImport::cancel() {
  cancel_ = true;
  release();
}

void TerrainImport::reset() {
  if (busy()) {
    cancel();
    join();
  }
  state_ = State::kIdle;
  info_.reset();
  raster_.reset();
}

double TerrainImport::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

double TerrainImport::eta_s() const {
  const float f = progress_.load();
  return f > 0.0f ? elapsed_s() * (1.0 - f) / f : -1.0;
}

Status TerrainImport::start_read(EditorSession& session, const fs::path& file) {
  if (busy()) return make_error(ErrorCode::kInvalidArgument, "an import is already running; wait for it or cancel it");
  reset();
  scene::Scene& scene = session.scene();
  const scene::SceneDocument& doc = scene.document();
  const bool mesh = is_mesh(file);
  section_ = mesh ? "model_terrain" : doc.has_module("terrain") || !doc.has_module("ground") ? "terrain" : "ground";
  ElevationReadOptions options;
  options.plain_extent = 4000.0;  // HeightSourceSettings::size's default
  if (doc.has_module(section_) && !mesh) {
    settings_from_scene(options, scene, section_ + ".elevation.");
    auto size = scene.get_param(section_ + ".size");
    if (size.ok()) options.plain_extent = std::strtod(size->c_str(), nullptr);
  }
  file_ = file;
  scene_ = &scene;
  job_status_.reset();
  done_ = false;
  cancel_ = false;
  progress_ = 0.0f;
  started_ = std::chrono::steady_clock::now();
  state_ = State::kReading;
  worker_ = std::thread([this, mesh, options] {
    TerrainSourceInfo info;
    info.file = file_;
    if (mesh) {
#if SYLVA_EDITOR_TERRAIN_IMPORT
      Result<terrain::PolygonMesh> m = terrain::load_mesh(file_);
      if (m.ok()) {
        info.kind = TerrainSourceInfo::Kind::kMesh;
        info.vertices = m->positions.size();
        info.faces = m->face_count();
        info_ = info;
      }
      job_status_ = m.ok() ? ok_status() : Status(m.error());
#else
      job_status_ = make_error(ErrorCode::kUnsupported, "the editor was built without the terrain module (no meshes)");
#endif
    } else {
      Result<ElevationRaster> r = read_elevation(file_, options);
      if (r.ok()) {
        info.reader = r->reader;
        info.crs = r->crs;
        info.columns = r->field.columns();
        info.rows = r->field.rows();
        info.spacing = r->field.spacing();
        info.source_spacing_x = r->source_spacing_x;
        info.source_spacing_z = r->source_spacing_z;
        info.min_height = r->field.min_height();
        info.max_height = r->field.max_height();
        info.nodata_filled = r->nodata_filled;
        info_ = info;
        raster_ = std::move(*r);
      }
      job_status_ = r.ok() ? ok_status() : Status(r.error());
    }
    done_ = true;
  });
  return ok_status();
}

Status TerrainImport::use_directly(EditorSession& session) {
  if (state_ != State::kRead || !info_) return make_error(ErrorCode::kInvalidArgument, "no terrain source was read yet");
  SYLVA_TRY(apply(session, false));
  reset();
  return ok_status();
}

Status TerrainImport::start_bake(EditorSession& session, const fs::path& out, bool hold) {
  if (state_ != State::kRead || !raster_) {
    return make_error(ErrorCode::kInvalidArgument, "no elevation raster was read to bake (a mesh is used directly)");
  }
  if (section_ != "terrain") {
    return make_error(ErrorCode::kInvalidArgument,
                      "baking needs a terrain section; this scene's ground is a \"ground\" section (use the raster directly)");
  }
  std::error_code ec;
  if (out.empty() || fs::equivalent(out, file_, ec)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: name another file for the baked terrain", out.string()));
  }
#if !SYLVA_EDITOR_TERRAIN_IMPORT
  (void)session;
  (void)hold;
  return make_error(ErrorCode::kUnsupported, "the editor was built without the terrain module (no baking)");
#else
  terrain::BakeOptions options;
  if (session.scene().document().has_module("terrain")) settings_from_scene(options.tree, session.scene(), "terrain.tree.");
  out_ = out;
  scene_ = &session.scene();
  job_status_.reset();
  done_ = false;
  cancel_ = false;
  progress_ = 0.0f;
  hold_ = hold;
  started_ = std::chrono::steady_clock::now();
  state_ = State::kBaking;
  options.control.cancel = &cancel_;
  options.control.progress = [this](float f) {
    progress_ = f;
    std::unique_lock<std::mutex> lock(hold_mutex_);
    if (!hold_) return;
    held_ = true;
    hold_cv_.notify_all();
    hold_cv_.wait(lock, [this] { return !hold_; });
    held_ = false;
  };
  worker_ = std::thread([this, options] {
    Result<terrain::BakeReport> report = terrain::bake_chunk_file(std::move(raster_->field), out_, options);
    raster_.reset();
    job_status_ = report.ok() ? ok_status() : Status(report.error());
    if (report.ok()) progress_ = 1.0f;
    std::lock_guard<std::mutex> lock(hold_mutex_);
    done_ = true;
    hold_cv_.notify_all();
  });
  return ok_status();
#endif
}

std::optional<Result<std::string>> TerrainImport::wait(EditorSession& session) {
  release();
  join();
  poll(session);
  return take_last();
}

std::optional<Result<std::string>> TerrainImport::take_last() {
  std::optional<Result<std::string>> last = std::move(last_);
  last_.reset();
  return last;
}

std::optional<Result<std::string>> TerrainImport::poll(EditorSession& session) {
  if (!busy() || !done_) return std::nullopt;
  last_ = finish(session);
  return last_;
}

Result<std::string> TerrainImport::finish(EditorSession& session) {
  join();
  const Status status = job_status_.value_or(make_error(ErrorCode::kInvalidArgument, "the import job ended without a result"));
  if (state_ == State::kReading) {
    if (!status.ok()) {
      reset();
      return status.error();
    }
    state_ = State::kRead;
    return "read " + info_->summary();
  }
  state_ = State::kIdle;
  if (!status.ok()) {
    info_.reset();
    return status.error();
  }
  std::error_code ec;
  const auto bytes = fs::file_size(out_, ec);
  const Status applied = apply(session, true);
  info_.reset();
  if (!applied.ok()) return applied.error();
  return std::string(fmt::format("baked {} ({:.1f} MB, 100 % in {:.1f} s); terrain.baked_file = {}", out_.string(),
                                         static_cast<double>(ec ? 0 : bytes) / 1e6, elapsed_s(),
                                         scene_relative(session.scene().document(), out_)));
}

Status TerrainImport::apply(EditorSession& session, bool baked) {
  scene::Scene& scene = session.scene();
  if (&scene != scene_) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("another scene was opened during the import; {} was not added to it",
                                  (baked ? out_ : file_).string()));
  }
  const nlohmann::json doc = scene.document().to_json();
  const nlohmann::json before = doc.contains(section_) ? doc[section_] : nlohmann::json();
  nlohmann::json after = before;
  if (after.is_null()) {
    scene::SceneDocument probe;
    auto added = probe.add_module(section_);
    if (!added.ok()) return added.error();
    after = probe.to_json()[section_];
  }
  const std::string label = fmt::format("import terrain {}", file_.filename().string());
  if (info_->kind == TerrainSourceInfo::Kind::kMesh) {
    after["file"] = scene_relative(scene.document(), file_);
  } else {
    // A painted height map wins over the raster (scene/height_source.hpp): importing under
    // unsaved strokes would show nothing; a saved map file is dropped from the section instead.
    if (const scene::SceneMap* map = scene.map(section_ + ".height"); map && map->unsaved()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}.height has unsaved painting, which would hide the imported terrain: save or undo it first",
                                    section_));
    }
    after["elevation"]["file"] = scene_relative(scene.document(), file_);
    if (auto maps = after.find("maps"); maps != after.end() && maps->is_object()) {
      maps->erase("height");
      if (maps->empty()) after.erase("maps");
    }
    if (section_ == "terrain") after["baked_file"] = baked ? scene_relative(scene.document(), out_) : "";
    if (baked) {
      // The bake's field starts at (0, 0) and the ground comes from the file's heights; centred
      // there, the raster (elevation.file) lies where the baked terrain did once baked_file is cleared.
      after["center"] = {0.5 * (info_->columns - 1) * info_->spacing, 0.5 * (info_->rows - 1) * info_->spacing};
    }
  }
  SYLVA_TRY(session.write_section(section_, after));
  session.history().push({label, {SectionEdit{section_, before, after}}});
  return ok_status();
}

}  // namespace sylva::editor
