#pragma once
// GL test support for the image-based levels: a Forest of one broadleaf tree with slices baked at
// a small resolution, forced to one level or left to its LOD selection, rendered and masked.

#include <sylva/core/image.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/vegetation/forest.hpp>

#include "support/gl_scene.hpp"

namespace sylva::vegetation::testing {

// One broadleaf (seed 1, leaf_size px leaf textures, 64 px bark) at the origin; no shadow maps; no
// bake cache.
Forest make_lod_forest(int slice_resolution = 128, SpeciesPreset preset = SpeciesPreset::kBroadleaf, int leaf_size = 64);

// Forces every instance to `level` (0, 1, 2) through the thresholds, or restores `natural`
// thresholds when level < 0; resets the LOD state (no hysteresis carried over).
void force_level(Forest& forest, int level, const LodSettings& natural = {});

// update + opaque draw into the scene's target; returns the picture.
Image render_forest(Forest& forest, GlScene& scene, const WindField& wind, double time);

// Foreground share of a picture rendered over scene.clear_color.
Image foreground(const Image& picture, const glm::vec4& clear);
double share(const Image& mask);

}  // namespace sylva::vegetation::testing
