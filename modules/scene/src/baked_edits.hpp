#pragma once
// The painted heights of a baked terrain, kept in the scene's edit layer (issue 15, "painting a
// streamed terrain: strokes go into a sparse edit layer of tiles saved next to the scene"). The
// ground map of a section streaming terrain.baked_file is saved as its map slot's own file, the
// per-map convention of Scene::save ("<stem>_maps/terrain_height.sylvaedits", copied on save-as,
// written in the save's transaction), but in the sparse tile format of terrain/edit_layer.hpp
// instead of a whole-field image: only the 256^2 tiles that differ from the baked heights.

#include <sylva/core/result.hpp>
#include <sylva/scene/map_grid.hpp>
#include <sylva/scene/scene_document.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace sylva::scene {

inline constexpr const char* kEditLayerExtension = ".sylvaedits";

bool is_edit_layer_file(const std::filesystem::path& file);

// The chunk file the section `module` streams its ground from (its height source's elevation file
// is a chunk file), resolved against the document; nullopt for any other ground.
std::optional<std::filesystem::path> baked_ground_file(const SceneDocument& document, const std::string& module);

// Applies the layer `file` over `grid` (the baked ground, read_baked_ground). A bad layer (missing,
// damaged, another version, another field, painted over other baked heights) is a warning naming
// the file (and tile) and the grid stays the baked heights: the scene opens without the edits and
// the file is left as it is. Returns whether the edits were applied.
bool apply_edit_layer_file(MapGrid& grid, const std::filesystem::path& file);

// Writes to `temp` (a FileTransaction writer; errors name `target`) the tiles of `painted` that
// differ from the heights baked into `chunk_file`; a ground of every n-th baked sample (a field
// above the ground limit) is diffed against the baked heights at that stride, so its layer holds
// ground samples. Errors: the chunk file's (named), a ground of another size (kUnsupported).
Status write_edit_layer_file(const MapGrid& painted, const std::filesystem::path& chunk_file,
                             const std::filesystem::path& temp, const std::filesystem::path& target);

}  // namespace sylva::scene
