#pragma once
// The seed's full-grid chunk meshes, -hq 0/1/2 (seed 002 §3.3 "Tessellation modes"; settings.hpp
// Tessellation), beside the RTIN of chunk_tree.cpp. A level's mesh keeps every point of its grid
// (step s root intervals); each grid square is split into 2 triangles along a fixed diagonal
// (hq0), along the diagonal whose ends differ less in height (hq1), or into 4 triangles around a
// centre vertex at the mean of the 4 corners (hq2). The surface of a level is a pure function of
// the level and the point (the diagonal follows from the square's own corners), so every chunk
// and every morph target agrees on it.

#include "rtin.hpp"

#include <sylva/terrain/chunk_tree.hpp>

#include <cstdint>

namespace sylva::terrain::detail {

// Height [m] of a level's surface (grid step `step` root intervals, hq0/hq1/hq2) at root-grid
// coordinates (px, pz) in [0, N]; a point on a square's border belongs to either square (the
// surface is continuous there). Asserts tessellation != kRtin.
double grid_surface_height(const HeightGrid& heights, Tessellation tessellation, std::int32_t step, double px,
                           double pz);

// What one chunk's grid mesh is built from.
struct GridChunkInput {
  const HeightGrid* heights = nullptr;
  Tessellation tessellation = Tessellation::kHq0;
  int level = 0, levels = 1;
  std::int32_t x0 = 0, z0 = 0, size = 0;  // the chunk's square [root intervals]
  std::int32_t columns = 1, rows = 1;     // field samples (beyond: padding, `outside`)
};

// Triangulates the chunk (up-facing triangles), fills every vertex but morph_error (intro_level =
// coarsest level whose grid holds the point as a corner, or the chunk's level for an hq2 centre;
// morph_target = the next coarser level's surface there) and returns the measured error: the
// largest |mesh - field| over the field samples inside the chunk.
double build_grid_chunk(const GridChunkInput& in, ChunkMesh& mesh);

}  // namespace sylva::terrain::detail
