#pragma once
// Deterministic, world-anchored blade placement (seed 001 §2.6 "Geometry creation", improved).
//
// Height fields: the world x/z plane is cut into square tiles of tile_size anchored at the world
// origin (tile (i, k) covers [i, i+1) x [k, k+1) times tile_size). For each tile:
//  - count = stochastic rounding of density * (exact integral of the density map over the tile),
//    with the rounding random taken from hash(tile, seed): |count - expected| < 1 for every
//    tile and the field total is unbiased. Seed 001 instead draws a fixed count per tile and
//    discards blades at random, which only matches the map on average.
//  - blade i sits at the i-th point of the R2 low-discrepancy sequence (Roberts 2018) rotated by
//    a per-tile hash, mapped through the tile's density CDF (a K x K grid of exact cell
//    integrals). Any prefix of the sequence is evenly spread, so thinning by rank keeps an even
//    cover (culling.hpp), and a small change of the map moves blades a little instead of
//    reshuffling them.
//  - every other random of blade i (orientation, height, width, bend, stiffness, colour) is a
//    hash of (tile, i, seed, k): nothing depends on the camera, on the order tiles are made in,
//    or on the extent of the field, so regenerating any region gives bit-identical blades.
//
// Triangle meshes (grass on any surface, Jahrmann & Wimmer 2017): each triangle gets
// stochastic-rounded area * mean vertex density * density blades at hashed barycentric points,
// growing along the interpolated normal. The hash key is the triangle's vertex positions, so the
// blades stay put when the mesh is re-indexed. Blades are grouped into tiles by the world cell
// (tile_size cubes) of their root, for culling.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/grass/blade.hpp>
#include <sylva/grass/maps.hpp>
#include <sylva/grass/settings.hpp>
#include <sylva/grass/uv_density_map.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::grass {

// World tile coordinates (y is 0 on height fields; the vertical cell on meshes).
struct TileKey {
  std::int32_t x = 0;
  std::int32_t y = 0;
  std::int32_t z = 0;
  bool operator==(const TileKey&) const = default;
};

// A contiguous run of blades with conservative bounds for culling.
struct GrassTile {
  TileKey key;
  std::uint32_t first = 0;        // index into BladeSet::blades
  std::uint32_t count = 0;
  glm::vec3 bounds_min{0.0f};     // BladeSet-local; holds every pose a blade can take
  glm::vec3 bounds_max{0.0f};
  double expected = 0.0;          // density integral times density: the ideal count
};

struct BladeSet {
  glm::dvec3 origin{0.0};         // world position that blade coordinates are relative to
  std::vector<Blade> blades;
  std::vector<GrassTile> tiles;
  float max_height = 0.0f;        // tallest blade [m]
  double expected_total() const;  // sum of the tiles' ideal counts
};

// Hard cap on the blades of one field, so a typo in density cannot exhaust memory.
inline constexpr std::size_t kMaxBlades = std::size_t{1} << 25;  // 33.5 million (3.2 GB)

// The world tiles [x0, x1) x [z0, z1) of a grid of `tile_size` m that overlap `area`.
// kLimit (naming grass.field.tile_size) for more than 4 million tiles or 1 million along a side.
struct TileRange {
  std::int64_t x0 = 0, x1 = 0, z0 = 0, z1 = 0;
};
Result<TileRange> tiles_overlapping(const Rect& area, double tile_size);

// The ideal (real-valued) and the generated blade count of one height-field tile.
double tile_expected_blades(const GrassFieldSettings& field, const GrassMaps& maps, TileKey key);
std::uint32_t tile_blade_count(const GrassFieldSettings& field, const GrassMaps& maps, TileKey key);

// A point placed by the tile sampler: world x/z, its hash (key for further randoms) and its
// rank among the tile's points in [0, 1) (prefixes are evenly spread).
struct TilePoint {
  glm::dvec2 position{0.0};
  std::uint32_t hash = 0;
  float rank = 0.0f;
};
// The placement of the header comment for any kind of element (blades, billboard clumps):
// stochastic-rounded density integral * per_m2 points of tile `key` of a world grid of
// tile_size, R2 sequence through the density CDF. Deterministic in (seed, key).
std::vector<TilePoint> sample_tile_points(const GrassMaps& maps, TileKey key, double tile_size, double per_m2,
                                          std::uint32_t seed);

// Appends the blades of one tile (origin = the BladeSet origin they are relative to).
void generate_tile(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                   const HeightField& ground, TileKey key, const glm::dvec3& origin, std::vector<Blade>& out);

// Every tile overlapping maps.rect(). Errors: invalid settings (messages name the parameter),
// an empty ground, more than kMaxBlades blades (kLimit).
Result<BladeSet> generate_blades(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                 const HeightField& ground, const glm::dvec3& origin);

// Tile-local regeneration after a map edit: regenerates, in place, the tiles of `set` that
// overlap `area` (world x/z, clipped to maps.rect()) from `maps`. `set` must come from
// generate_blades (or this function) with the same settings, ground and origin, and the maps
// may differ from the ones it was made with only inside `area`; then the result equals
// generate_blades(field, blade, maps, ground, set.origin) bit for bit (blades are a function of
// their tile alone, see the header comment). Returns the index of the first blade that may
// differ (blades before it are untouched). Errors as generate_blades.
Result<std::uint32_t> regenerate_tiles(BladeSet& set, const GrassFieldSettings& field, const BladeSettings& blade,
                                       const GrassMaps& maps, const HeightField& ground, const Rect& area);

// A triangle mesh to grow grass on, positions relative to the BladeSet origin [m]. normals and
// density (per vertex, [0, 1]) may be empty: face normals and density 1 are used then.
struct GroundMesh {
  std::span<const glm::vec3> positions;
  std::span<const glm::vec3> normals;
  std::span<const std::uint32_t> indices;  // 3 per triangle
  std::span<const float> density;
};

// Density over the mesh's texture coordinates (issue 16): the blade density is `map` at each
// root's UV, interpolated from corner_uvs (3 per triangle, parallel to GroundMesh::indices), and
// GroundMesh::density is ignored. Each triangle draws its candidates at density 1
// (stochastic-rounded area * field.density) and keeps candidate i when map(uv_i) > a hash of
// (triangle, i), so an edge of the map crosses triangles sharply and the count is unbiased.
struct MeshUvDensity {
  std::span<const glm::vec2> corner_uvs;
  const UvDensityMap& map;
};

// Errors: indices out of range or not a multiple of 3, size mismatch of normals/density/corner_uvs,
// non-finite positions, too many blades (with uv: counted at density 1). `uv` is not kept.
Result<BladeSet> generate_blades_on_mesh(const GrassFieldSettings& field, const BladeSettings& blade,
                                         const GroundMesh& mesh, const glm::dvec3& origin,
                                         const MeshUvDensity* uv = nullptr);

// Validates the placement settings; errors name "grass.field.<name>" / "grass.blade.<name>".
Status check_settings(const GrassFieldSettings& field, const BladeSettings& blade);

}  // namespace sylva::grass
