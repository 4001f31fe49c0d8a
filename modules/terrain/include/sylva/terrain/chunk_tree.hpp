#pragma once
// The chunk quadtree of a height field, built offline (seed 002 §2.2 after Ulrich 2002).
//
// Grid. The field's samples are the points of a square "root grid" of N x N intervals,
// N = (leaf_dimension - 1) * 2^(levels - 1), the smallest such N covering the field. Points
// beyond the field (non-square and non-power-of-two fields) are padding: their height is the
// nearest field sample (clamped), they are flagged `outside`, are never counted in the measured
// error, and the renderer discards their fragments. Chunks lying wholly in padding are absent.
//
// Levels. Level 0 is the root (one chunk, coarsest; the seed's "LOD 1"); level l has 2^l x 2^l
// chunk positions of N / 2^l intervals and a grid step of 2^(levels - 1 - l) root intervals, so
// every chunk has leaf_dimension vertices per side at its own level's resolution.
//
// Meshes. Every level's mesh is a right-triangulated irregular network (RTIN, longest-edge
// bisection) of that level's grid with the vertices dropped whose removal changes the surface by
// at most flat_tolerance * spacing ("reduced where flat"). The leaf level drops only vertices
// whose removal changes nothing (exactly interpolated ones): leaves cannot be refined, so their
// error would escape the screen-space bound when the camera comes close; with exact leaves the
// bound holds at any distance. Because the vertex set of a level is
// a single global set (a point is in it or not, whichever chunk asks), chunks of the same level
// share identical edge vertices, and every level's triangulation refines the coarser level's.
// The error delta of a chunk is MEASURED: the largest vertical distance between its mesh and the
// full-resolution field over every field sample inside the chunk. Since the meshes are nested
// right triangulations this is the exact maximum over the whole chunk area, not a sample of it.
// error_bound (used for selection) is delta made monotone: a parent's bound is at least its
// children's bound / (1 - max_morph_fraction).
//
// Morphing data. Each vertex carries the height of the next coarser level's surface at its
// position (morph_target) and the error of the coarser chunk(s) there (morph_error); both depend
// only on the point, never on the chunk that holds it, so every chunk computes the same morphed
// position for a shared point (see vertex_position.hpp). Coordinates: x/z ground plane, y up,
// metres; grid point (gx, gz) is field sample (gx, gz) at world origin + (gx, gz) * spacing.
//
// Tessellation (settings.hpp): the seed's hq0/hq1/hq2 modes replace the RTIN by the level's full
// grid (grid_tessellation.hpp): same levels, chunks, measured errors, morph data and seams (edge
// vertices are the level's grid points, so same-level chunks share them); hq2 adds a centre
// vertex per square whose height is interpolated, not a field sample.

#include <sylva/core/height_field.hpp>
#include <sylva/core/result.hpp>
#include <sylva/terrain/settings.hpp>

#include <glm/glm.hpp>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sylva::terrain {

// Chunk edges in the order an up-facing (normal +y) boundary walks them:
// west x = x0 (z increasing), north z = z1 (x increasing), east x = x1 (z decreasing),
// south z = z0 (x decreasing). The opposite edge of e is (e + 2) % 4.
enum Edge : std::uint8_t { kWest = 0, kNorth = 1, kEast = 2, kSouth = 3 };

struct ChunkKey {
  int level = 0;
  std::uint32_t x = 0;  // chunk column at its level
  std::uint32_t z = 0;  // chunk row at its level
  bool operator==(const ChunkKey&) const = default;
};

struct ChunkVertex {
  std::uint32_t gx = 0, gz = 0;  // root-grid point
  float height = 0.0f;           // metres; the clamped field sample
  float morph_target = 0.0f;     // metres; coarser level's surface here (= height if intro_level == 0)
  float morph_error = 0.0f;      // metres; error_bound of the coarser chunk(s) containing the point
  std::uint8_t intro_level = 0;  // coarsest level whose mesh contains the point
  std::uint8_t outside = 0;      // 1 = padding (outside the field)
  // 1 = the point is (gx + 0.5, gz + 0.5): the centre of a leaf square of an hq2 tree (settings.hpp
  // Tessellation), whose height is the mean of the square's corners. 0 in RTIN/hq0/hq1 trees.
  std::uint8_t centre = 0;
};

struct ChunkMesh {
  std::vector<ChunkVertex> vertices;
  std::vector<std::uint32_t> indices;                // triangles, up-facing (counter-clockwise from above)
  std::array<std::vector<std::uint32_t>, 4> edges;   // vertices on each Edge, by increasing coordinate
};

struct Chunk {
  ChunkKey key;
  bool present = false;        // false: wholly outside the field, never built or drawn
  float error = 0.0f;          // measured delta [m]
  float error_bound = 0.0f;    // monotone delta used by selection and morphing [m]
  float min_y = 0.0f, max_y = 0.0f;  // height range of the mesh including morph targets [m]
  std::uint32_t triangle_count = 0;
  std::uint32_t vertex_count = 0;
  ChunkMesh mesh;              // empty when ChunkTreeSettings::keep_meshes is false
};

// What per-frame selection reads of a chunk, packed apart from the (large) Chunk so the tree
// walk touches one cache line per chunk: cached world bounds and the error bounds.
struct ChunkNode {
  glm::dvec3 lo{0.0}, hi{0.0};  // world bounds of the rendered geometry (x/z clipped to the field)
  float error_bound = 0.0f;     // Chunk::error_bound [m]
  float parent_bound = 0.0f;    // the parent's error_bound (own bound at the root) [m]
  std::uint32_t x = 0, z = 0;   // ChunkKey
  std::uint8_t level = 0;
  std::uint8_t present = 0;
};

struct LevelReport {
  int level = 0;
  std::uint32_t chunks = 0;
  std::uint64_t triangles = 0;      // after flat reduction
  std::uint64_t grid_triangles = 0; // what the level's full grid would have (2 per square, 4 in hq2)
  float max_error = 0.0f;           // largest measured delta of the level [m]
};

struct BuildReport {
  double total_ms = 0.0;
  double error_grid_ms = 0.0;  // vertex-error pass over the root grid
  double meshes_ms = 0.0;      // triangulation, measurement, vertex-cache optimisation
  int threads = 1;
  std::vector<LevelReport> levels;
  std::uint64_t triangles() const;
  // Multi-line human-readable report: time, threads, triangles and max error per level.
  std::string describe() const;
};

// Progress in [0, 1] (called from the building thread) and cancellation (checked between chunks).
struct BuildControl {
  std::function<void(float)> progress;
  const std::atomic<bool>* cancel = nullptr;
};

// What ChunkTree::rebuild_region changed, as chunk indices (ascending). The renderer re-uploads
// rebuilt + updated; bounds_only chunks keep their mesh and only changed their error_bound.
struct RegionRebuild {
  std::vector<std::uint32_t> rebuilt;      // re-triangulated and re-measured
  std::vector<std::uint32_t> updated;      // mesh kept; morph_target / morph_error (and min_y/max_y) changed
  std::vector<std::uint32_t> bounds_only;  // only error_bound (selection data) changed
  double ms = 0.0;                         // CPU time of the call
};

class ChunkTree {
 public:
  ChunkTree() = default;

  // Errors: invalid settings (kInvalidArgument naming the parameter), an empty field, NaN/Inf
  // samples (kInvalidArgument with their count and first sample; repair them with
  // HeightFieldImageOptions::non_finite = kRepair when loading), a grid above max_build_bytes
  // (kLimit), cancellation (kCancelled).
  static Result<ChunkTree> build(const HeightField& field, const ChunkTreeSettings& settings,
                                 const BuildControl& control = {});

  // Updates the tree in place after the samples in the rectangle [x0, x1) x [z0, z1) (field
  // columns x rows; x1/z1 EXCLUSIVE, clamped to the field) of `field` changed; `field` is the whole
  // edited field, of the size, spacing and origin the tree was built from. Afterwards every chunk
  // equals what build(field) would give (vertices, indices, error, error_bound, bounds).
  // Rebuilt: every present chunk whose square grown by half a chunk on each side meets the
  // edited samples (a point on a chunk edge has an error diamond reaching half a chunk into the
  // neighbour, rtin.hpp), at every level; an edit on a chunk corner therefore rebuilds all chunks
  // sharing the corner. Then the monotone error bounds are recomputed up the tree, the morph data
  // of other chunks is refreshed where the coarser surface or bounds changed (`updated`), and the
  // selection nodes and report are recomputed. Cost: the padded height and error grids are
  // recomputed in full (O(N^2), a few ms at 257^2), the chunk meshes only for `rebuilt`.
  // Errors: keep_meshes false (kInvalidArgument; the morph data lives in the meshes), a tree of
  // the seed's hq tessellations (kInvalidArgument: rebuild it whole), a field of
  // another size/spacing/origin or NaN/Inf samples in the rectangle (kInvalidArgument); the tree
  // is unchanged on error. An empty rectangle changes nothing.
  Result<RegionRebuild> rebuild_region(const HeightField& field, int x0, int z0, int x1, int z1);

  int levels() const { return levels_; }
  std::uint32_t leaf_intervals() const { return n_; }          // leaf_dimension - 1
  std::uint32_t root_intervals() const { return root_n_; }     // N
  std::uint32_t chunks_per_side(int level) const { return 1u << level; }
  std::uint32_t chunk_size(int level) const { return root_n_ >> level; }  // root intervals
  std::uint32_t step(int level) const { return 1u << (levels_ - 1 - level); }

  std::size_t chunk_count() const { return chunks_.size(); }
  std::uint32_t index(int level, std::uint32_t x, std::uint32_t z) const;
  const Chunk& chunk(std::uint32_t index) const { return chunks_[index]; }
  // nullptr when (x, z) is out of range or the chunk is absent.
  const Chunk* find(int level, std::int64_t x, std::int64_t z) const;
  std::uint32_t parent_index(std::uint32_t index) const;
  // Children in the order (x, z), (x+1, z), (x, z+1), (x+1, z+1); asserts level < levels - 1.
  std::array<std::uint32_t, 4> child_indices(std::uint32_t index) const;

  // Field geometry.
  int field_columns() const { return columns_; }
  int field_rows() const { return rows_; }
  double spacing() const { return spacing_; }
  glm::dvec2 origin() const { return origin_; }
  // World-space bounds of a chunk's rendered geometry (x/z clipped to the field); cached.
  void chunk_bounds(std::uint32_t index, glm::dvec3& lo, glm::dvec3& hi) const {
    lo = nodes_[index].lo;
    hi = nodes_[index].hi;
  }
  // Selection data of every chunk, indexed like chunk().
  const std::vector<ChunkNode>& nodes() const { return nodes_; }
  // First chunk index of a level (chunks of a level are stored row by row).
  std::uint32_t level_offset(int level) const { return level_offset_[static_cast<std::size_t>(level)]; }
  // World x/z of a root-grid point.
  glm::dvec2 grid_to_world(std::uint32_t gx, std::uint32_t gz) const {
    return origin_ + glm::dvec2(gx, gz) * spacing_;
  }

  const ChunkTreeSettings& settings() const { return settings_; }
  const BuildReport& report() const { return report_; }
  bool has_meshes() const { return settings_.keep_meshes; }

 private:
  friend class ChunkTreeBuilder;
  friend class ChunkFile;
  ChunkTreeSettings settings_;
  int levels_ = 0;
  std::uint32_t n_ = 0;
  std::uint32_t root_n_ = 0;
  int columns_ = 0, rows_ = 0;
  double spacing_ = 1.0;
  glm::dvec2 origin_{0.0};
  std::vector<std::uint32_t> level_offset_;
  std::vector<Chunk> chunks_;
  std::vector<ChunkNode> nodes_;
  BuildReport report_;
  void compute_nodes();
  void compute_error_bounds();
  float morph_error_of(const ChunkVertex& v) const;
  void fill_level_report();
};

}  // namespace sylva::terrain
