// The painted heights of a baked terrain as the scene's edit layer (baked_edits.hpp).
#include "baked_edits.hpp"

#include "baked_ground.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>
#include <sylva/scene/module_registry.hpp>

#if SYLVA_HAS_TERRAIN
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/edit_layer.hpp>
#endif

#include <fmt/format.h>

namespace sylva::scene {

bool is_edit_layer_file(const std::filesystem::path& file) { return file.extension() == kEditLayerExtension; }

std::optional<std::filesystem::path> baked_ground_file(const SceneDocument& document, const std::string& module) {
  const ModuleSection* section = document.module(module);
  const ModuleDescriptor* d = find_module(module);
  if (section == nullptr || d == nullptr || !d->provides_ground || !d->height_source) return std::nullopt;
  const std::string& file = d->height_source(*section->settings).elevation.file;
  if (file.empty()) return std::nullopt;
  const std::filesystem::path path = document.resolve(file);
  if (path.extension() != ".sylvaterrain" && !is_chunk_file(path)) return std::nullopt;
  return path;
}

bool apply_edit_layer_file(MapGrid& grid, const std::filesystem::path& file) {
#if SYLVA_HAS_TERRAIN
  auto layer = terrain::read_edit_layer(file);
  Status applied = layer.ok() ? terrain::apply_edit_layer(*layer, grid.values, grid.width, grid.height, file)
                              : Status(layer.error());
  if (!applied.ok()) {
    log_warn("{}; the scene opens without these edits (the file is left as it is)", applied.error().message);
    return false;
  }
  log_info("{}: {} painted tile(s) over the baked heights", file.string(), layer->tiles.size());
  return true;
#else
  log_warn("{}: edits of a baked terrain need the terrain module, which this program was built without", file.string());
  (void)grid;
  return false;
#endif
}

Status write_edit_layer_file(const MapGrid& painted, const std::filesystem::path& chunk_file,
                             const std::filesystem::path& temp, const std::filesystem::path& target) {
#if SYLVA_HAS_TERRAIN
  auto file = terrain::ChunkFile::open(chunk_file);
  if (!file.ok()) return make_error(file.error().code, fmt::format("{}: {}", target.string(), file.error().message));
  // The ground is the field or every stride-th sample of it (baked_ground.hpp): the layer holds
  // the ground's own samples, diffed against the baked heights at that stride (the overview), and
  // the section derives the painted exact field from them (terrain/decimated_ground_edits.hpp).
  const int columns = (*file)->tree().field_columns(), rows = (*file)->tree().field_rows();
  const int stride = painted.width > 1 ? (columns - 1) / (painted.width - 1) : 0;
  if (stride < 1 || (columns - 1) / stride + 1 != painted.width || (rows - 1) / stride + 1 != painted.height) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: the ground is {}x{} samples, neither the {}x{} baked in {} nor every n-th of "
                                  "them: it cannot be saved as its edit layer",
                                  target.string(), painted.width, painted.height, columns, rows, chunk_file.string()));
  }
  auto baked = (*file)->read_heights(stride);
  if (!baked.ok()) return make_error(baked.error().code, fmt::format("{}: {}", target.string(), baked.error().message));
  const terrain::EditLayer layer = terrain::diff_edit_layer(baked->samples(), painted.values, painted.width, painted.height);
  return write_new_file(temp, terrain::encode_edit_layer(layer), target);
#else
  (void)painted, (void)chunk_file, (void)temp;
  return make_error(ErrorCode::kUnsupported, fmt::format("{}: needs the terrain module", target.string()));
#endif
}

}  // namespace sylva::scene
