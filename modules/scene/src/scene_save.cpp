// Scene::save: a scene file and its maps saved as one transaction (core/file_transaction.hpp),
// so a save succeeds or fails as a whole and never leaves a scene pointing at maps it did not
// save. Where each map goes:
//  - an edited map is written into the saved scene's own map folder, "<stem>_maps/<module>_<slot>
//    .<exr|png>": a user's source image is never overwritten, and a "save as" never writes into
//    the original scene's maps;
//  - the painted ground of a baked terrain (terrain.baked_file) is saved as its edit layer,
//    "<stem>_maps/terrain_height.sylvaedits": only the 256^2 tiles that differ from the baked
//    heights (baked_edits.hpp), not a whole-field image;
//  - on a "save as" (another file than the one the document came from) every unedited map given
//    by a relative path is copied byte for byte into the new scene's own map folder, so the two
//    scenes share no map file that either could later overwrite;
//  - otherwise an unedited map keeps its file; a relative path is rewritten for the new folder;
//  - a source file a setting names (an elevation raster, a species file, a mesh, a voxel species
//    table or palette: by the scenes' convention a string setting called `file` or `*_file`,
//    resolved against the scene file, scene_document.hpp) is only referenced, its relative path
//    rewritten for the new folder: it is read-only source data, a raster often too large to copy.
// The scene file is staged last and so renamed last. The in-memory document and maps change only
// after the commit succeeded.

#include <sylva/scene/scene.hpp>

#include "baked_edits.hpp"

#include <sylva/core/file_transaction.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <system_error>

namespace sylva::scene {
namespace {

namespace fs = std::filesystem;

fs::path folder_or_dot(const fs::path& folder) { return folder.empty() ? fs::path(".") : folder; }

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

}  // namespace

bool names_scene_file(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  const std::string_view last = dot == std::string_view::npos ? path : path.substr(dot + 1);
  return last == "file" || last.ends_with("_file");
}

namespace {

// `path` (relative to old_dir, or absolute) as seen from new_dir.
std::string rebase(const std::string& path, const fs::path& old_dir, const fs::path& new_dir) {
  const fs::path p(path);
  const fs::path from = absolute_normal(folder_or_dot(old_dir));
  const fs::path to = absolute_normal(folder_or_dot(new_dir));
  if (p.is_absolute() || from == to) return path;
  const fs::path target = (from / p).lexically_normal();
  const fs::path rel = target.lexically_relative(to);
  return rel.empty() ? target.string() : rel.string();
}

std::string own_map_path(const fs::path& scene_file, std::string_view module, std::string_view slot,
                         std::string_view extension) {
  return fmt::format("{}_maps/{}_{}{}", scene_file.stem().string(), module, slot, extension);
}

std::string default_extension(MapKind kind) { return kind == MapKind::kHeight ? ".exr" : ".png"; }

Status copy_into(const fs::path& source, const fs::path& temp, const fs::path& target) {
  std::error_code ec;
  fs::copy_file(source, temp, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot copy the map {} ({})", target.string(), source.string(),
                                                  ec.message()));
  }
  return ok_status();
}

// One map slot's outcome: the path the saved scene records and, when a file is written, how.
struct MapPlan {
  std::string path;
  FileTransaction::Writer write;  // empty: the file stays where it is
};

}  // namespace

Status Scene::save(const std::filesystem::path& file) {
  const fs::path new_dir = file.parent_path();
  const fs::path old_dir = document_->directory();
  const bool save_as = document_->file().empty() || absolute_normal(document_->file()) != absolute_normal(file);
  const fs::path base = folder_or_dot(new_dir);

  // Plan every slot first: (module section, slot) -> plan.
  std::map<std::pair<std::string, std::string>, MapPlan> plans;
  for (const auto& [id, map] : maps_) {
    if (!document_->module(map.module)) continue;
    MapPlan plan;
    const SceneMap* m = &map;
    if (map.unsaved() && map.slot == "height" && baked_ground_file(*document_, map.module)) {
      // The painted ground of a baked terrain: the sparse edit layer (baked_edits.hpp).
      plan.path = own_map_path(file, map.module, map.slot, kEditLayerExtension);
      plan.write = [m, baked = *baked_ground_file(*document_, map.module)](const fs::path& temp, const fs::path& target) {
        return write_edit_layer_file(m->grid, baked, temp, target);
      };
    } else if (map.unsaved()) {
      plan.path = own_map_path(file, map.module, map.slot, default_extension(map.kind));
      plan.write = [m](const fs::path& temp, const fs::path& target) {
        if (m->grid.empty()) {
          return Status(make_error(ErrorCode::kInvalidArgument, fmt::format("{}: the map is empty", target.string())));
        }
        const Image image = map_to_image(m->grid, m->file_scale, m->file_offset, target);
        return write_image_file(temp, image, image.format(), target);
      };
    } else if (map.path.empty()) {
      continue;  // a generated map nobody edited: nothing to save
    } else {
      plan.path = rebase(map.path, old_dir, new_dir);
    }
    plans[{map.module, map.slot}] = std::move(plan);
  }
  for (const ModuleSection& section : document_->modules()) {
    for (const auto& [slot, path] : section.maps) {
      auto key = std::make_pair(section.name, slot);
      if (!plans.count(key)) plans[key] = MapPlan{rebase(path, old_dir, new_dir), {}};
      MapPlan& plan = plans[key];
      if (!save_as || plan.write || fs::path(path).is_absolute()) continue;
      const fs::path source = document_->resolve(path);
      std::error_code ec;
      if (!fs::is_regular_file(source, ec)) continue;  // a missing map stays a (reported) reference
      plan.path = own_map_path(file, section.name, slot, source.extension().string());
      plan.write = [source](const fs::path& temp, const fs::path& target) { return copy_into(source, temp, target); };
    }
  }

  // The saved document: the same settings with the planned map paths.
  SceneDocument saved = *document_;
  for (ModuleSection& section : saved.modules()) {
    // Source files named by settings are the user's, referenced and never copied (a raster may be
    // gigabytes): a save into another folder rebases their relative paths to the same files.
    for (const ParamDescriptor& param : sylva::describe_params(*section.settings)) {
      if (!names_scene_file(param.path) || param.ref.type != ParamType::kString) continue;
      auto& source = *static_cast<std::string*>(param.ref.ptr);
      if (!source.empty()) source = rebase(source, old_dir, new_dir);
    }
    for (auto& [slot, path] : section.maps) path = plans.at({section.name, slot}).path;
    for (const auto& [key, plan] : plans) {
      if (key.first == section.name) section.maps[key.second] = plan.path;
    }
  }

  std::error_code ec;
  const fs::path own_folder = base / (file.stem().string() + "_maps");
  const bool writes_maps = std::any_of(plans.begin(), plans.end(), [](const auto& kv) { return bool(kv.second.write); });
  const bool created_folder = writes_maps && !fs::exists(own_folder, ec);
  if (writes_maps) {
    fs::create_directories(own_folder, ec);
    if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the folder: {}", own_folder.string(), ec.message()));
  }
  FileTransaction transaction;
  Status status = ok_status();
  for (const auto& [key, plan] : plans) {
    if (!plan.write) continue;
    status = transaction.stage(base / plan.path, plan.write);
    if (!status.ok()) break;
  }
  if (status.ok()) status = transaction.stage_bytes(file, saved.to_text());
  if (status.ok()) status = transaction.commit();
  if (!status.ok()) {
    if (created_folder) fs::remove(own_folder, ec);  // only if still empty
    return status;
  }

  // Committed: the scene now is what was saved.
  for (auto& [id, map] : maps_) {
    auto it = plans.find({map.module, map.slot});
    if (it == plans.end()) continue;
    map.path = it->second.path;
    map.saved_revision = map.revision;
  }
  for (ModuleSection& section : document_->modules()) section.maps = saved.module(section.name)->maps;
  document_->set_file(file);
  return ok_status();
}

}  // namespace sylva::scene
