#pragma once
// A triangle mesh read as a height field over x/z (issue 16: grass on any mesh gets the seed-003
// far field "where the surface is a height field"). The far field (far_field.hpp) stands on a
// HeightField and reads a density map over a rectangle; this rasterises a mesh into both.
//
// Rasterisation: sample points on a grid of `spacing` over the x/z bounds of the mesh's upward
// faces; a sample is covered by every face whose x/z projection contains it (edges inclusive) and
// takes that face's interpolated height and density. The mesh is a height field when
//  - no face with an x/z footprint faces down (normal y < -1e-4 after normalising: an overhang,
//    a box's bottom, or a mesh wound the other way, whose blades also grow downwards), and
//  - no sample is covered by two faces at heights further apart than 1e-4 of the mesh's size
//    (plus 0.1 mm): a roof over a floor, a fold.
// Vertical faces (|normal y| <= 1e-4) have no footprint and are skipped. Overlaps smaller than the
// spacing between samples are not seen. Samples no face covers take the height of the nearest
// covered sample (so the far field's ground layer does not dive at the mesh's outline) and
// density 0 (so no far grass grows there).

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/grass/maps.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <span>

namespace sylva::grass {

struct MeshHeightField {
  HeightField heights;  // world x/z and y [m]; sample (i, j) at origin + (i, j) * spacing
  Image density;        // one texel per height sample, [0, 1]; 0 where no face covers it
  Rect rect;            // the density image's world rectangle: texel centres on the samples
  std::size_t covered = 0;  // samples some face covers
};

// Density of the mesh at barycentric coordinates `bary` of triangle `triangle`, in [0, 1].
using MeshDensityAt = std::function<float(std::uint32_t triangle, const glm::vec3& bary)>;

// `positions` relative to `origin` [m], `indices` 3 per triangle (checked: in range), `spacing` > 0
// [m]. Errors: kInvalidArgument saying why the mesh is not a height field (which face, where),
// or that no face faces up; kLimit when the grid would exceed `max_samples`.
Result<MeshHeightField> mesh_height_field(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                                          const glm::dvec3& origin, double spacing, const MeshDensityAt& density,
                                          std::size_t max_samples = std::size_t{1} << 22);

}  // namespace sylva::grass
