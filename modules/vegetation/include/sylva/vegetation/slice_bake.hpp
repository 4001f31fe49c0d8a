#pragma once
// Baking the image-based levels (seed 000 §2.6, §3.3): slice clusters rendered from the rest-pose
// LOD0 tree with GL render-to-texture, and their disk cache (the seed's future work, §6.1).
//
// Slice sets (object space, shared by every instance of a species; seed Fig. 3.16):
//   LOD1 = 3 vertical slice directions 60 degrees apart x 3 parallel slices each,
//   LOD2 = 2 perpendicular slices (one each).
// Direction j has normal n_j = (sin a_j, 0, cos a_j), a_j = j pi / directions, horizontal axis
// a_j = (cos a_j, 0, -sin a_j) and vertical axis y. The tree's horizontal extent around the centre
// of its bounds is a radius R; slice (j, i) holds the slab n_j . (p - c) in
// [-R + i T, -R + (i + 1) T], T = 2R / layers (seed eq. 4.1), rendered orthographically from +n_j
// with near/far planes at the slab faces, and sits at the slab centre.
//
// Per slice texel (rows bottom-up, as GL stores them):
//   colour  RGBA8: bark albedo, or the leaf colour texture (deviation c_v + 0.5; the season c_s is
//                  added when drawing, §3.3 "without the seasonal component"); alpha = covered;
//   normal  RGBA8: slice-space normal (a, y, n) * 0.5 + 0.5; alpha 0 bark, 0.25 + 0.75
//                  leafSpecificNumber on leaves (the seed's 4th channel, §2.12);
//   depth   R32F : offset of the visible surface from the slice plane along n [m] (for shadows,
//                  §2.13);
//   branch  RGBA32F: x = index of the level-1 branch the texel belongs to (-1: trunk only; leaves
//                  take their branch's level-1 ancestor), y = x on that branch, z = x on the trunk
//                  (the attachment of the level-1 branch, or the trunk point itself), w = root
//                  (trunk) branch + 1 where geometry was drawn, -(root + 1) elsewhere. Texels without geometry take the values of the nearest
//                  drawn texel (Voronoi cells by jump flooding, the seed's "data propagation" of
//                  §2.7); so do the colour and normal channels (colour alpha stays 0), so filtered
//                  lookups and mipmaps never bleed black into edges.
// The stored x coordinates replace the seed's x = |OP| / L approximation (§2.7) in the backward
// transform: the displacement is evaluated at the rest texel's own x.
//
// Cache: a binary file per bake (magic, format version, a 64-bit key of everything the bake
// depends on, payload size and an FNV-1a 64 checksum of the payload), written atomically through
// core (write_file_atomic). A file with a wrong magic, version, key, size or checksum is rejected
// with kCorrupt and rebaked; the rebake overwrites it.

#include <sylva/core/hash.hpp>
#include <sylva/core/result.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::vegetation {

class TreeAsset;
struct TreeTextureSet;

struct SliceLayout {
  int directions = 3;
  int layers = 3;
  glm::vec3 center{0.0f};  // x, z: centre of the horizontal extent; y: middle of the height
  float radius = 1.0f;     // horizontal half-width R [m]
  float half_height = 1.0f;
  float margin = 0.0f;     // quads grow by this on every side [m] (content sways outside)

  int count() const { return directions * layers; }
  float angle(int direction) const;
  glm::vec3 axis(int direction) const;    // a_j
  glm::vec3 normal(int direction) const;  // n_j
  float thickness() const { return 2.0f * radius / static_cast<float>(layers); }
  float layer_offset(int layer) const;    // slab centre along n_j relative to the centre [m]
  // Bake projection of slice (direction, layer): object space -> clip space (depth 1 at the slab
  // face nearest the camera, 0 at the far face; for GL_ZERO_TO_ONE and GL_GREATER).
  glm::mat4 bake_matrix(int direction, int layer) const;
};

// Bounds of the rest mesh: horizontal radius around the bounds centre, height; `margin_share`
// of the height grows the quads.
SliceLayout make_slice_layout(const TreeMesh& mesh, int directions, int layers, float margin_share);

struct SliceImages {
  int resolution = 0;  // texels per side
  int count = 0;       // slices (layer index = direction * layers + layer)
  std::vector<std::uint8_t> color;   // count * res^2 * 4
  std::vector<std::uint8_t> normal;  // count * res^2 * 4
  std::vector<float> depth;          // count * res^2
  std::vector<float> branch;         // count * res^2 * 4

  std::size_t texels() const { return static_cast<std::size_t>(count) * static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution); }
  bool operator==(const SliceImages&) const = default;
};

struct BakedLod {
  SliceLayout layout;
  SliceImages images;
};

struct BakedTree {
  std::array<BakedLod, 2> lod;  // [0] = LOD1 (3 x 3), [1] = LOD2 (2 x 1)
  double bake_ms = 0.0;         // wall time of the GL bake (0 when loaded from the cache)
  bool from_cache = false;
};

// Fills uncovered texels from their nearest covered texel (jump flooding, 8 neighbours per step,
// steps N/2 .. 1 plus one extra step of 1). Returns, per texel, the index of the covered texel it
// copies (-1 when the slice has none). Exposed for tests.
std::vector<std::int32_t> nearest_covered(const std::vector<std::uint8_t>& covered, int resolution);

// Renders the slices of both levels from the rest pose (needs a current GL 4.5 context; saves and
// restores the framebuffer, viewport, clip control and depth state it touches). resolution in
// [16, 1024]. kGl when a bake program does not build, kInvalidArgument for a bad resolution.
Result<BakedTree> bake_tree_slices(const TreeAsset& asset, const TreeMesh& mesh, int resolution, float margin_share);

// Cache key: mesh vertices and records, the texture images, resolution, margin, format version.
std::uint64_t slice_cache_key(const TreeMesh& mesh, const TreeTextureSet& textures, int resolution, float margin_share);
using sylva::fnv1a64;  // core/hash.hpp

std::string serialize_slices(const BakedTree& tree, std::uint64_t key);
// kCorrupt naming what is wrong (magic, version, key, size, checksum, dimensions).
Result<BakedTree> deserialize_slices(const std::string& bytes, std::uint64_t key);
Status save_slice_cache(const std::filesystem::path& file, const BakedTree& tree, std::uint64_t key);
Result<BakedTree> load_slice_cache(const std::filesystem::path& file, std::uint64_t key);
// "<directory>/slices-<key as 16 hex digits>.bin".
std::filesystem::path slice_cache_file(const std::filesystem::path& directory, std::uint64_t key);
// The folder for a LodSettings::cache_directory value ("auto" = <temp>/sylva-lod-cache, "" = none).
std::filesystem::path resolve_cache_directory(const std::string& setting);

// Load from the cache when a valid file exists, otherwise bake and (when a folder is given) save.
// A corrupt file is logged, rebaked and replaced; a failed save is logged, not an error.
Result<BakedTree> bake_or_load_slices(const TreeAsset& asset, const TreeMesh& mesh, const TreeTextureSet& textures,
                                      int resolution, float margin_share, const std::filesystem::path& cache_directory);

}  // namespace sylva::vegetation
