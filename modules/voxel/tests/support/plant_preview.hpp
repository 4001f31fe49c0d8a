#pragma once
// CPU preview of plant models (side and top orthographic views) for looking at grammars
// without a GL context. Output 0 is drawn brown, 1 green, others grey; nearer blocks are brighter.

#include <sylva/core/image.hpp>
#include <sylva/voxel/plant.hpp>

#include <filesystem>
#include <vector>

namespace sylva::voxel::testing {

// Several models side by side, each as a side view (x-y) above a top view (x-z), `cell` pixels
// per model column.
Image preview_plants(const std::vector<const PlantModel*>& models, int cell = 160);
void save_preview(const std::filesystem::path& path, const std::vector<const PlantModel*>& models);

}  // namespace sylva::voxel::testing
