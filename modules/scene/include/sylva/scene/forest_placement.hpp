#pragma once
// Where the trees of a forest stand (GL-free; the scene's "vegetation" section uses it).
//
// World-anchored jittered grid: the x/z plane is cut into square cells of side
// cell = 100 m / sqrt(trees_per_hectare) anchored at the world origin. Cell (i, k) holds at most
// one candidate at a hashed position inside the cell, kept at least min_spacing / 2 from the
// cell's border (so two trees are never closer than min_spacing when min_spacing <= cell), and
// accepted when a second hash is below the painted density at that point. Every random of a tree
// (position, yaw, scale, phase, colour) is a hash of (seed, i, k), so:
//  - the forest does not depend on the order or extent of evaluation;
//  - editing the density or the ground in a region changes only the trees of the cells that
//    region touches (place_trees over a sub-rectangle gives exactly the trees of the full
//    placement whose cells overlap it);
//  - trees stand on the ground: y = ground height at the trunk base.

#include <sylva/core/height_field.hpp>
#include <sylva/core/params.hpp>
#include <sylva/scene/map_grid.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace sylva::scene {

// kJittered: one candidate at a hashed point of each cell, kept with probability = density (a
// natural stand). kGrid: the thesis experiments' exact layouts (seed 000 Tab 5.1/5.3/5.5): trees at
// every multiple of the cell side 100 m / sqrt(trees_per_hectare) from the world origin inside
// the area, kept where the density is at least 0.5; an area around the origin smaller than a cell
// gives one tree at (0, 0).
enum class ForestLayout { kJittered, kGrid };
constexpr std::array<EnumName<ForestLayout>, 2> enum_names(ForestLayout) {
  return {{{ForestLayout::kJittered, "jittered"}, {ForestLayout::kGrid, "grid"}}};
}

struct ForestPlacement {
  glm::dvec2 area_min{-60.0, -60.0};  // the forest's rectangle (world x/z) [m]
  glm::dvec2 area_max{60.0, 60.0};
  float trees_per_hectare = 30.0f;    // at density 1
  float min_spacing = 4.0f;           // metres between trunks (capped at the cell size)
  float scale_min = 0.8f;             // random uniform scale range
  float scale_max = 1.2f;
  std::uint32_t seed = 1;
  // Natural clearings: the share of the area [0, 0.95] left open where a low-frequency fBm of
  // the position (feature size clearing_size metres) is lowest, with soft thinning edges. The
  // noise threshold is the share's quantile over the whole area, so placing a sub-rectangle gives
  // the same trees as placing the whole forest.
  float clearings = 0.0f;
  float clearing_size = 150.0f;
  ForestLayout layout = ForestLayout::kJittered;
};

struct PlacedTree {
  glm::dvec3 position{0.0};  // trunk base, world metres (y on the ground)
  float yaw = 0.0f;          // radians
  float scale = 1.0f;
  float phase = 0.0f;        // [0, 1): animation time offset / season offset / colour randoms
  float random = 0.0f;       // [0, 1): a second independent random
  glm::ivec2 cell{0};        // the grid cell it belongs to
};

// Cell side length [m].
double forest_cell_size(const ForestPlacement& p);

// Trees of every cell overlapping `region` (clipped to the forest area). `density` may be null
// (density 1 everywhere inside the area); `ground` may be null (y = 0).
std::vector<PlacedTree> place_trees(const ForestPlacement& p, const MapGrid* density, const HeightField* ground,
                                    glm::dvec2 region_min, glm::dvec2 region_max);

// The cells overlapping a region: [min, max] inclusive cell indices.
void forest_cells(const ForestPlacement& p, glm::dvec2 region_min, glm::dvec2 region_max, glm::ivec2& cell_min,
                  glm::ivec2& cell_max);

}  // namespace sylva::scene
