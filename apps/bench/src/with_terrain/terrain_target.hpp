#pragma once
// "builtin:terrain": the terrain module's LOD pipeline (chunk tree, screen-space or seed
// distance selection, morphing, seams or skirts; modules/terrain) drawn by the bench itself,
// until the terrain module's own renderer is part of modules/scene. Per frame the CPU selects
// chunks and assembles the frame's triangles with the module's vertex formula
// (terrain::assemble_frame), which the module's shader reproduces operation for operation, and
// the bench draws them in one call with normals from the full-resolution field. CPU time
// therefore includes assembly and upload, which a GPU-morphing renderer would not pay.
//
// Parameters: terrain.field.* (generated fBm field), terrain.tree.* (chunk tree build; trees are
// cached across settings with the same field and tree settings), terrain.lod.* (per-frame
// selection: max_pixel_error, criterion, lod_distance, morph_fraction, crack_fix, frustum_cull)
// and lighting.*. Metrics per frame: terrain.max_projected_error_px (largest K * delta / (D - delta)
// over the drawn chunks with the measured delta: the screen-space geometric error actually drawn,
// whichever criterion selected it), terrain.selection_ms, terrain.chunks, and the chunks per level
// as LOD instances "terrain.level<k>".

#include "bench_target.hpp"

namespace sylva::bench {

inline constexpr const char* kBuiltinTerrain = "builtin:terrain";

std::unique_ptr<BenchTarget> make_terrain_target();

}  // namespace sylva::bench
